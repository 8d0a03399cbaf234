#include "localizer/models/observation_factory.hpp"

#include <stdexcept>

namespace conicloc::localizer {

const std::vector<ObservationModelEntry>& observation_models() {
  static const std::vector<ObservationModelEntry> models{
      {.name = "conic-beam",
       .make =
           [](const ObservationConfig& config, const maps::PlaneMap& map,
              const sensor::LaserCalibration& calibration) -> std::unique_ptr<ObservationModel> {
         return std::make_unique<ConicBeamModel>(map, calibration, config.sensor, config.conic_beam,
                                                 config.shortcuts);
       },
       .max_beams_option = "--beams",
       .max_beams_help = "Beams scored per scan by conic-beam (0: all)",
       .max_beams = [](ObservationConfig& config) -> std::size_t& {
         return config.conic_beam.beams.max_beams;
       },
       .cull_back_faces = [](ObservationConfig& config) -> bool& {
         return config.conic_beam.cull.cull_back_faces;
       }},
      {.name = "conic-segment",
       .make =
           [](const ObservationConfig& config, const maps::PlaneMap& map,
              const sensor::LaserCalibration& calibration) -> std::unique_ptr<ObservationModel> {
         return std::make_unique<ConicSegmentModel>(map, calibration, config.sensor,
                                                    config.conic_segment, config.shortcuts);
       },
       // It scores every measured segment: no cap.
       .max_beams_option = "",
       .max_beams_help = "",
       .cull_back_faces = [](ObservationConfig& config) -> bool& {
         return config.conic_segment.cull.cull_back_faces;
       }},
      {.name = "point-to-plane",
       .make = [](const ObservationConfig& config, const maps::PlaneMap& map,
                  const sensor::LaserCalibration&) -> std::unique_ptr<ObservationModel> {
         return std::make_unique<PointToPlaneModel>(map, config.sensor, config.point_to_plane);
       },
       .max_beams_option = "--points",
       .max_beams_help = "Points scored per scan by point-to-plane (0: all)",
       .max_beams = [](ObservationConfig& config) -> std::size_t& {
         return config.point_to_plane.beams.max_beams;
       }},
  };
  return models;
}

std::vector<std::string> observation_model_names() {
  std::vector<std::string> names;
  for (const auto& model : observation_models()) names.push_back(model.name);
  return names;
}

const ObservationModelEntry* find_observation_model(const std::string& name) {
  for (const auto& model : observation_models()) {
    if (model.name == name) return &model;
  }
  return nullptr;
}

const ObservationModelEntry& observation_model(const std::string& name) {
  if (const ObservationModelEntry* model = find_observation_model(name)) return *model;
  std::string known;
  for (const auto& each : observation_model_names()) known += (known.empty() ? "" : ", ") + each;
  throw std::invalid_argument("unknown observation model '" + name + "' (known: " + known + ")");
}

std::unique_ptr<ObservationModel> make_observation_model(
    const ObservationConfig& config, const maps::PlaneMap& map,
    const sensor::LaserCalibration& calibration) {
  return observation_model(config.model).make(config, map, calibration);
}

}  // namespace conicloc::localizer
