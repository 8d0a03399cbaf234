#include "localizer/models/observation_factory.hpp"

#include <stdexcept>

namespace conicloc::localizer {

std::vector<std::string> observation_model_names() {
  return {"conic-beam", "conic-segment", "point-to-plane"};
}

void ObservationConfig::set_max_range(double max_range_m) {
  conic_beam.beams.max_range_m = max_range_m;
  conic_beam.mixture.max_range_m = max_range_m;
  conic_beam.predictor.max_range_m = max_range_m;
  conic_beam.cull.max_range_m = max_range_m;
  conic_segment.segmentation.max_range_m = max_range_m;
  conic_segment.mixture.max_range_m = max_range_m;
  conic_segment.predictor.max_range_m = max_range_m;
  conic_segment.cull.max_range_m = max_range_m;
  point_to_plane.beams.max_range_m = max_range_m;
}

std::unique_ptr<ObservationModel> make_observation_model(
    const ObservationConfig& config, const maps::PlaneMap& map,
    const sensor::LaserCalibration& calibration) {
  if (config.model == "conic-beam") {
    return std::make_unique<ConicBeamModel>(map, calibration, config.conic_beam);
  }
  if (config.model == "conic-segment") {
    return std::make_unique<ConicSegmentModel>(map, calibration, config.conic_segment);
  }
  if (config.model == "point-to-plane") {
    return std::make_unique<PointToPlaneModel>(map, config.point_to_plane);
  }
  std::string known;
  for (const auto& name : observation_model_names()) known += (known.empty() ? "" : ", ") + name;
  throw std::invalid_argument("unknown observation model '" + config.model + "' (known: " + known +
                              ")");
}

}  // namespace conicloc::localizer
