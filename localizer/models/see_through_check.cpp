#include "localizer/models/see_through_check.hpp"

#include <cmath>

namespace conicloc::localizer {

SeeThroughCheck::SeeThroughCheck(const maps::PlaneMap& map,
                                 const sensor::LaserCalibration& calibration,
                                 const SeeThroughConfig& config, double max_range_m)
    : map_(map),
      config_(config),
      max_range_m_(max_range_m),
      predictor_(map, calibration, config.predictor, max_range_m),
      index_(map),
      culler_(map, index_, calibration, config.cull, max_range_m) {}

SeeThroughCheck::~SeeThroughCheck() = default;

SeeThroughResult SeeThroughCheck::evaluate(const sensor::Scan& scan,
                                           const Pose3& T_map_sensor) const {
  SeeThroughResult result;
  const auto selected = select_beams(scan, config_.beams, max_range_m_);
  const std::vector<int> candidates = culler_.cull(T_map_sensor).kept;
  predictor_.predict(T_map_sensor, candidates, predicted_);
  const int rings = static_cast<int>(predicted_.rings.size());
  std::vector<double> azimuths_rad, predicted_m;
  for (std::size_t r = 0; r < selected.size(); ++r) {
    if (selected[r].empty() || static_cast<int>(r) >= rings) continue;
    azimuths_rad.clear();
    for (const SelectedBeam& beam : selected[r]) azimuths_rad.push_back(beam.azimuth_rad);
    predicted_m.resize(azimuths_rad.size());
    const PredictedRing& ring = predicted_.ring(static_cast<int>(r));
    ring.evaluate_sorted(azimuths_rad, predicted_m);
    for (std::size_t i = 0; i < predicted_m.size(); ++i) {
      // No surface predicted (a gap, or out of the sensor's range): a return there is clutter or
      // an unmapped space, not evidence against the pose.
      if (!std::isfinite(predicted_m[i])) continue;
      // Walls only: a beam past a predicted floor or ceiling also follows from a height error
      // (a stair, a sloped floor) or an opening the model lacks (a stairwell), and those are not
      // the filter being lost in the plan.
      const int polygon = ring.polygon[ring.piece_at(azimuths_rad[i])];
      if (polygon < 0 ||
          std::abs(map_.polygons[static_cast<std::size_t>(polygon)].plane.normal.z()) >
              config_.max_wall_normal_z)
        continue;
      ++result.beams;
      const double margin = config_.margin_m + config_.relative_margin * predicted_m[i];
      if (selected[r][i].range_m > predicted_m[i] + margin) ++result.see_through;
    }
  }
  return result;
}

}  // namespace conicloc::localizer
