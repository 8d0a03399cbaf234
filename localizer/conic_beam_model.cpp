#include "localizer/conic_beam_model.hpp"

namespace conicloc::localizer {

namespace {

struct ConicScratch final : ObservationModel::Scratch {
  PredictedScan predicted;
  std::vector<double> ranges_m;
};

}  // namespace

ConicBeamModel::ConicBeamModel(const maps::PlaneMap& map,
                               const sensor::LaserCalibration& calibration,
                               const ConicBeamConfig& config)
    : config_(config),
      mixture_(config.mixture),
      predictor_(map, calibration, config.predictor),
      index_(map),
      culler_(map, index_, calibration, config.cull) {}

ConicBeamModel::~ConicBeamModel() = default;

void ConicBeamModel::prepare(const sensor::Scan& scan, const Eigen::AlignedBox3d& cloud_box) {
  rings_.clear();
  beam_count_ = 0;
  const auto selected = select_beams(scan, config_.beams);
  const int predicted_rings = static_cast<int>(predictor_.rings().size());
  for (std::size_t r = 0; r < selected.size(); ++r) {
    // Scan rings are indexed like the predictor's (by elevation rank); extra rings are ignored.
    if (selected[r].empty() || static_cast<int>(r) >= predicted_rings) continue;
    RingBeams ring;
    ring.ring = static_cast<int>(r);
    std::vector<double> azimuths;
    for (const SelectedBeam& beam : selected[r]) {
      azimuths.push_back(beam.azimuth_rad);
      ring.ranges_m.push_back(beam.range_m);
      ring.floors.push_back(mixture_.floor(beam.range_m));
    }
    ring.azimuths.assign(azimuths);
    beam_count_ += azimuths.size();
    rings_.push_back(std::move(ring));
  }
  Eigen::AlignedBox3d region = cloud_box;
  if (!region.isEmpty()) {
    region.min().array() -= config_.cull_margin_m;
    region.max().array() += config_.cull_margin_m;
    candidates_ = culler_.cull(region).kept;
  } else {
    candidates_.clear();
  }
}

std::unique_ptr<ObservationModel::Scratch> ConicBeamModel::make_scratch() const {
  return std::make_unique<ConicScratch>();
}

ObservationScore ConicBeamModel::score(const Pose3& T_map_sensor, Scratch* scratch) const {
  ObservationScore result;
  if (beam_count_ == 0) return result;
  ConicScratch local;
  ConicScratch& work = scratch ? static_cast<ConicScratch&>(*scratch) : local;
  predictor_.predict(T_map_sensor, candidates_, work.predicted);
  std::size_t inliers = 0;
  for (const RingBeams& ring : rings_) {
    const std::size_t n = ring.ranges_m.size();
    work.ranges_m.resize(n);
    work.predicted.ring(ring.ring).evaluate_sorted(ring.azimuths, work.ranges_m);
    // The hot loop: one mixture term per beam.
    for (std::size_t i = 0; i < n; ++i) {
      bool inlier = false;
      result.log_likelihood +=
          mixture_.log_likelihood(ring.ranges_m[i], work.ranges_m[i], ring.floors[i], inlier);
      inliers += inlier ? 1 : 0;
    }
  }
  result.inlier_fraction = static_cast<double>(inliers) / static_cast<double>(beam_count_);
  return result;
}

}  // namespace conicloc::localizer
