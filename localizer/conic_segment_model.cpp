#include "localizer/conic_segment_model.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "localizer/association_grid.hpp"

namespace conicloc::localizer {

struct ConicSegmentModel::SegmentScratch final : ObservationModel::Scratch {
  AssociationCache<Association> associations;
  PredictedScan predicted;
  std::vector<double> planes;  ///< per landmark: n_s (3) and D_s in the particle's frame
};

ConicSegmentModel::ConicSegmentModel(const maps::PlaneMap& map,
                                     const sensor::LaserCalibration& calibration,
                                     const ConicSegmentConfig& config)
    : config_(config),
      mixture_(config.mixture),
      predictor_(map, calibration, config.predictor),
      index_(map),
      culler_(map, index_, calibration, config.cull) {}

ConicSegmentModel::~ConicSegmentModel() = default;

void ConicSegmentModel::prepare(const sensor::Scan& scan, const Eigen::AlignedBox3d& cloud_box) {
  ++scan_generation_;
  fits_.clear();
  returns_ = 0;
  const int predicted_rings = static_cast<int>(predictor_.rings().size());
  for (std::size_t r = 0; r < scan.rings.size() && static_cast<int>(r) < predicted_rings; ++r) {
    for (const ConicSegment& segment : segment_scan_line(scan.rings[r], config_.segmentation)) {
      fits_.push_back(make_segment_fit(scan.rings[r], segment, static_cast<int>(r),
                                       config_.segmentation.min_range_m,
                                       config_.segmentation.max_range_m));
      returns_ += static_cast<std::size_t>(fits_.back().returns);
    }
  }
  Eigen::AlignedBox3d region = cloud_box;
  candidates_.clear();
  if (!region.isEmpty()) {
    region.min().array() -= config_.cull_margin_m;
    region.max().array() += config_.cull_margin_m;
    candidates_ = culler_.cull(region).kept;
  }
}

std::unique_ptr<ObservationModel::Scratch> ConicSegmentModel::make_scratch() const {
  return std::make_unique<SegmentScratch>();
}

Association ConicSegmentModel::association_at(const Pose3& T_map_sensor) const {
  SegmentScratch work;
  return cached_association(T_map_sensor, work);
}

const Association& ConicSegmentModel::cached_association(const Pose3& T_map_sensor,
                                                         SegmentScratch& work) const {
  // A new cell is predicted at its centre (a deterministic pose, whatever particle came first).
  return work.associations.get(
      T_map_sensor, scan_generation_, config_.association_cell_m, config_.association_angle_rad,
      [&](const Pose3& centre, Association& association) {
        predictor_.predict(centre, candidates_, work.predicted);
        associate_segments(fits_, work.predicted, predictor_.map(), predictor_.rings(),
                           config_.association_gate_m, association);
      });
}

ObservationScore ConicSegmentModel::score(const Pose3& T_map_sensor, Scratch* scratch) const {
  if (returns_ == 0) return {};
  SegmentScratch local;
  SegmentScratch& work = scratch ? static_cast<SegmentScratch&>(*scratch) : local;
  return score_association(T_map_sensor, cached_association(T_map_sensor, work), work);
}

ObservationScore ConicSegmentModel::score_association(const Pose3& T_map_sensor,
                                                      const Association& association,
                                                      SegmentScratch& work) const {
  const Eigen::Matrix3d& R = T_map_sensor.linear();
  const Eigen::Vector3d t = T_map_sensor.translation();
  const double min_inverse = 1.0 / config_.predictor.max_range_m;
  const double max_inverse = 1.0 / config_.predictor.min_range_m;
  const BeamFloor floor = mixture_.floor_without_short();
  double log_likelihood = 0.0;
  double outlier_returns = association.unassociated_returns;
  double inlier_returns = 0.0;
  // Each candidate plane in the particle's sensor frame: n_s = Rᵀn, D_s = D + n·t (DESIGN.md).
  std::vector<double>& planes = work.planes;
  planes.resize(4 * association.landmarks.size());
  for (std::size_t l = 0; l < association.landmarks.size(); ++l) {
    const Landmark& landmark = association.landmarks[l];
    const Eigen::Vector3d n_map(landmark.normal_map[0], landmark.normal_map[1],
                                landmark.normal_map[2]);
    const Eigen::Vector3d n = R.transpose() * n_map;
    planes[4 * l] = n.x();
    planes[4 * l + 1] = n.y();
    planes[4 * l + 2] = n.z();
    planes[4 * l + 3] = landmark.offset_map + n_map.dot(t);
  }
  for (const LandmarkSegment& segment : association.segments) {
    // The closest visible candidate: its conic p = n'/E, n' = (n_x cos φ, n_y cos φ, n_z sin φ)
    // (ring_conic.hpp), against the fit: (p − p_fit)ᵀM(p − p_fit) = (n'ᵀMn' − 2E n'·g + E²h)/E²,
    // one division and no square root per candidate.
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k < segment.candidate_count; ++k) {
      const double* plane = &planes[4 * static_cast<std::size_t>(segment.candidates[k])];
      const double E = -(plane[3] + plane[2] * segment.vertical_offset_m);
      if (E == 0.0) continue;
      const double v0 = plane[0] * segment.cos_elevation, v1 = plane[1] * segment.cos_elevation,
                   v2 = plane[2] * segment.sin_elevation;
      // Seen at a range within limits at the checks: 1/r = n'·x/E in (1/max, 1/min].
      bool visible = true;
      for (int c = 0; c < 3 && visible; ++c) {
        const double v = v0 * segment.check_cos[c] + v1 * segment.check_sin[c] + v2;
        visible = E > 0.0 ? (v > min_inverse * E && v <= max_inverse * E)
                          : (v < min_inverse * E && v >= max_inverse * E);
      }
      if (!visible) continue;
      const double* m = segment.m;
      const double mv0 = m[0] * v0 + m[1] * v1 + m[2] * v2;
      const double mv1 = m[1] * v0 + m[3] * v1 + m[4] * v2;
      const double mv2 = m[2] * v0 + m[4] * v1 + m[5] * v2;
      const double vmv = v0 * mv0 + v1 * mv1 + v2 * mv2;
      const double vg = v0 * segment.g[0] + v1 * segment.g[1] + v2 * segment.g[2];
      const double q = (vmv - 2.0 * E * vg + E * E * segment.h) / (E * E);
      best = std::min(best, std::max(q, 0.0));
    }
    if (!(best < std::numeric_limits<double>::infinity())) {
      outlier_returns += segment.returns;
      continue;
    }
    // One robust term per segment on its mean squared range difference, counted once per return
    // (the sum over its returns of a per-return term with that residual); the max-mixture form,
    // as this runs segments × particles times per scan.
    bool inlier = false;
    log_likelihood += segment.returns * mixture_.max_log_likelihood_squared(
                                            best * segment.inverse_returns, floor, inlier);
    inlier_returns += inlier ? segment.returns : 0.0;
  }
  log_likelihood += outlier_returns * floor.without_short;
  return {log_likelihood, inlier_returns / static_cast<double>(returns_)};
}

}  // namespace conicloc::localizer
