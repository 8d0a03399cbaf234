#include "localizer/models/conic_segment_model.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "localizer/conic/association_grid.hpp"
#include "localizer/conic/yaw_shared_prediction.hpp"
#include "localizer/models/correlated_terms.hpp"

namespace conicloc::localizer {

namespace {
// The fit a segment summarises: every one of its (segment, candidate) terms holds it.
int fit_of(const Association& association, const LandmarkSegment& segment) {
  return association.terms[static_cast<std::size_t>(segment.terms[0])].fit;
}
}  // namespace

struct ConicSegmentModel::SegmentScratch final : ObservationModel::Scratch {
  AssociationCache<CellAssociation> associations;
  PredictedScan predicted;
  YawSharedPrediction cell_predictions;
  std::vector<SensorPlaneTerms> planes;  ///< per landmark: its plane in the particle's frame
  Eigen::ArrayXd costs;                  ///< per term of the association (candidate_costs)
  Eigen::ArrayXd beyond;                 ///< per term: returns beyond its arc (segment_rims.hpp)
  std::vector<double> rim_shifts;        ///< returns_beyond_rims' working memory
};

ConicSegmentModel::ConicSegmentModel(const maps::PlaneMap& map,
                                     const sensor::LaserCalibration& calibration,
                                     const RangeSensor& sensor, const ConicSegmentConfig& config,
                                     const PredictionShortcuts& shortcuts)
    : config_(config),
      shortcuts_(shortcuts),
      max_range_m_(sensor.max_range_m),
      noise_(config.segment_noise),
      mixture_(config.mixture, config.segment_noise, sensor.max_range_m),
      floor_(mixture_.floor_without_short()),
      predictor_(
          map, calibration,
          cell_predictor_config(config.predictor, config.association_cell, sensor.max_range_m),
          sensor.max_range_m),
      index_(map),
      culler_(map, index_, calibration, config.cull, sensor.max_range_m),
      cloud_cull_(config.cull_margin_m, config.cull_slack_m),
      surfaces_(coplanar_surfaces(map)),
      grid_(association_grid(map, config.association_cell)) {}

ConicSegmentModel::~ConicSegmentModel() = default;

void ConicSegmentModel::prepare(const sensor::Scan& scan, const Eigen::AlignedBox3d& cloud_box) {
  ++scan_generation_;
  fit_weights_.clear();
  fits_.clear();
  fit_terms_.clear();
  scored_rings_.clear();
  returns_ = 0;
  const int predicted_rings = static_cast<int>(predictor_.rings().size());
  for (std::size_t r = 0; r < scan.rings.size() && static_cast<int>(r) < predicted_rings; ++r) {
    for (const ConicSegment& segment :
         segment_scan_line(scan.rings[r], config_.segmentation, max_range_m_)) {
      fits_.push_back(make_segment_fit(scan.rings[r], segment, static_cast<int>(r),
                                       config_.segmentation.min_range_m, max_range_m_));
      fit_terms_.push_back(candidate_term(fits_.back(), predictor_.rings()[r]));
      returns_ += static_cast<std::size_t>(fits_.back().returns);
      if (scored_rings_.empty() || scored_rings_.back() != static_cast<int>(r)) {
        scored_rings_.push_back(static_cast<int>(r));
      }
    }
  }
  cloud_cull_.update(culler_, cloud_box);
}

SurfaceTally ConicSegmentModel::explained_surfaces(const Association& association,
                                                   std::vector<int>* surface_of_fit) const {
  // The returns grouped by the surface (plane) their segment is associated with first; segments
  // that fit none count nothing (correlated_terms.hpp).
  SurfaceTally tally(surfaces_);
  if (surface_of_fit) surface_of_fit->assign(fits_.size(), -1);
  for (const LandmarkSegment& segment : association.segments) {
    const int polygon =
        association.landmarks[static_cast<std::size_t>(segment.candidates[0])].polygon;
    tally.add(polygon, segment.returns);
    if (surface_of_fit)
      (*surface_of_fit)[static_cast<std::size_t>(fit_of(association, segment))] =
          surfaces_.of_polygon[static_cast<std::size_t>(polygon)];
  }
  return tally;
}

double ConicSegmentModel::effective_terms(const Pose3& T_map_sensor, Scratch* scratch) const {
  std::unique_ptr<SegmentScratch> local;
  SegmentScratch& work = own_scratch(scratch, local);
  return explained_surfaces(cached_association(T_map_sensor, work).association, nullptr)
      .effective_terms(noise_.shared_error_correlation());
}

void ConicSegmentModel::weigh_terms(const Pose3& reference, Scratch* scratch) {
  std::unique_ptr<SegmentScratch> local;
  SegmentScratch& work = own_scratch(scratch, local);
  std::vector<int> surface_of_fit;
  const SurfaceTally tally =
      explained_surfaces(cached_association(reference, work).association, &surface_of_fit);
  double scan_returns = 0.0;
  for (const SegmentFit& fit : fits_) scan_returns += fit.returns;
  fit_weights_ = direction_term_weights(surface_of_fit, scan_returns, tally,
                                        noise_.shared_error_correlation());
  weighted_returns_ = 0.0;
  for (std::size_t f = 0; f < fits_.size(); ++f)
    weighted_returns_ += fit_weights_[f] * fits_[f].returns;
  if (std::all_of(fit_weights_.begin(), fit_weights_.end(), [](double w) { return w == 1.0; }))
    fit_weights_.clear();  // nothing raised: scored as without weights
}

std::unique_ptr<ObservationModel::Scratch> ConicSegmentModel::make_scratch() const {
  return std::make_unique<SegmentScratch>();
}

void ConicSegmentModel::set_pose_blur(double blur_m) {
  noise_ = with_pose_blur(config_.segment_noise, blur_m);
  mixture_ = BeamMixture(config_.mixture, noise_, max_range_m_);
}

Association ConicSegmentModel::association_at(const Pose3& T_map_sensor) const {
  SegmentScratch work;
  return cached_association(T_map_sensor, work).association;
}

const ConicSegmentModel::CellAssociation& ConicSegmentModel::cached_association(
    const Pose3& T_map_sensor, SegmentScratch& work) const {
  // A new cell is predicted at its centre (a deterministic pose, whatever particle came first).
  return work.associations.get(
      T_map_sensor, scan_generation_, grid_,
      [&](const AssociationCellKey& key, const Pose3& centre, CellAssociation& cell) {
        Association& association = cell.association;
        work.cell_predictions.predict(predictor_, key, cloud_cull_.candidates(),
                                      cloud_cull_.version(), scored_rings_, scan_generation_, grid_,
                                      shortcuts_.share_prediction_across_yaw, work.predicted);
        associate_segments(fits_, fit_terms_, work.predicted, predictor_.map(),
                           config_.association_gate_m, association);
        // A pose of the cell is within half a cell of the centre on each axis and angle/2 in
        // each of roll, pitch and yaw: |Δt| ≤ the half diagonal, rotation angle ≤ 3 · angle/2
        // (the triangle inequality on the Z-Y-X composition).
        mark_seen_throughout_cell(association, fit_terms_, centre,
                                  config_.association_cell.half_diagonal_m(),
                                  1.5 * config_.association_cell.angle_rad, 1.0 / max_range_m_,
                                  1.0 / config_.predictor.min_range_m);
        cell.centre = centre;
        cell.rims.clear();
        if (config_.rims) {
          find_segment_rims(association, fits_, work.predicted, predictor_.map(),
                            predictor_.rings(), surfaces_, centre, config_.association_cell,
                            cell.rims);
        }
      });
}

ObservationScore ConicSegmentModel::score(const Pose3& T_map_sensor, Scratch* scratch) const {
  if (returns_ == 0) return {};
  std::unique_ptr<SegmentScratch> local;
  SegmentScratch& work = own_scratch(scratch, local);
  return score_association(T_map_sensor, cached_association(T_map_sensor, work), work);
}

ObservationScore ConicSegmentModel::score_association(const Pose3& T_map_sensor,
                                                      const CellAssociation& cell,
                                                      SegmentScratch& work) const {
  const Association& association = cell.association;
  const double min_inverse = 1.0 / max_range_m_;
  const double max_inverse = 1.0 / config_.predictor.min_range_m;
  const BeamFloor& floor = floor_;
  // Each candidate plane in the particle's sensor frame: n_s = Rᵀn, D_s = D + n·t (DESIGN.md).
  std::vector<SensorPlaneTerms>& planes = work.planes;
  planes.resize(association.landmarks.size());
  for (std::size_t l = 0; l < association.landmarks.size(); ++l) {
    planes[l] = landmark_plane_terms(association.landmarks[l], T_map_sensor);
  }
  // Every (segment, candidate) cost, then one robust term per segment on its closest visible
  // candidate's mean squared range difference, counted once per return (the sum over its returns
  // of a per-return term with that residual); the max-mixture form, as this runs
  // segments × particles times per scan.
  Eigen::ArrayXd& costs = work.costs;
  candidate_costs(association, fit_terms_, planes, min_inverse, max_inverse, costs);
  returns_beyond_rims(cell.rims, pose_offset(cell.centre, T_map_sensor), association.terms.size(),
                      work.rim_shifts, work.beyond);
  const Eigen::ArrayXd& beyond = work.beyond;
  // With weights (weigh_terms()) each segment's term and its returns' floor count by its fit's
  // weight; the returns of segments this cell leaves unassociated are what the associated ones
  // leave of the scan's weighted total.
  const bool weighted = !fit_weights_.empty();
  double log_likelihood = 0.0;
  double outlier_returns = weighted ? weighted_returns_ : association.unassociated_returns;
  double inlier_returns = 0.0;
  for (const LandmarkSegment& segment : association.segments) {
    const double weight =
        weighted ? fit_weights_[static_cast<std::size_t>(fit_of(association, segment))] : 1.0;
    if (weighted) outlier_returns -= weight * segment.returns;
    // The candidate that explains the segment best: its returns within the polygon's arc on the
    // plane (n − b terms of the rms difference), the b beyond it unexplained.
    double best = -std::numeric_limits<double>::infinity();
    double best_inliers = 0.0;
    for (int k = 0; k < segment.candidate_count; ++k) {
      const int t = segment.terms[k];
      if (!(costs(t) < std::numeric_limits<double>::infinity())) continue;
      const double outside = std::min(beyond(t), segment.returns);
      bool inlier = false;
      const double on_plane = segment.returns - outside;
      const double value = on_plane * mixture_.max_log_likelihood_squared(
                                          costs(t) * segment.inverse_returns, floor, inlier) +
                           outside * floor.without_short;
      if (value > best) best = value, best_inliers = inlier ? on_plane : 0.0;
    }
    if (!(best > -std::numeric_limits<double>::infinity())) {
      outlier_returns += weight * segment.returns;
      continue;
    }
    log_likelihood += weight * best;
    inlier_returns += best_inliers;
  }
  log_likelihood += outlier_returns * floor.without_short;
  return {log_likelihood, inlier_returns / static_cast<double>(returns_)};
}

}  // namespace conicloc::localizer
