#pragma once
// Observation models by name: one config struct holding every model's settings, and the registry
// of the models (a model is its own file plus one entry here: its name, the option capping what it
// scores, what it needs from the map, and how it is built).

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "localizer/models/conic_beam_model.hpp"
#include "localizer/models/conic_segment_model.hpp"
#include "localizer/models/observation_model.hpp"
#include "localizer/models/point_to_plane_model.hpp"
#include "localizer/models/prediction_shortcuts.hpp"
#include "localizer/models/range_sensor.hpp"
#include "sensor/laser_calibration.hpp"

namespace conicloc::localizer {

struct ObservationConfig {
  std::string model = "conic-beam";  ///< one of observation_model_names()
  /// The sensor's maximum range and range noise: set here once, handed by every model (and the
  /// filter's lost test) to the parts that use them.
  RangeSensor sensor;
  ConicBeamConfig conic_beam;
  ConicSegmentConfig conic_segment;
  PointToPlaneConfig point_to_plane;
  /// Benches and tests only (the reference paths of the conic models); the tools keep the
  /// defaults.
  PredictionShortcuts shortcuts;
};

/// What the filter, the tools and the sweeps know of one observation model.
struct ObservationModelEntry {
  std::string name;
  /// Builds the model over `map` (which must outlive it) from its part of the config.
  std::unique_ptr<ObservationModel> (*make)(const ObservationConfig& config,
                                            const maps::PlaneMap& map,
                                            const sensor::LaserCalibration& calibration);
  /// The command-line option capping the beams (or points) it scores per scan, and its help;
  /// empty for a model that scores every measured segment (a sweep's `beams` does not apply).
  std::string max_beams_option;
  std::string max_beams_help;
  /// That cap in the config (0: all); null with the option.
  std::size_t& (*max_beams)(ObservationConfig& config) = nullptr;
  /// What it needs from the map: whether it culls a polygon seen from behind (a map that serves
  /// both sides of a wall with one face turns this off); null for a model that does not cull.
  bool& (*cull_back_faces)(ObservationConfig& config) = nullptr;
};

/// Every model, the default first, in the order the tools list them.
const std::vector<ObservationModelEntry>& observation_models();

/// The model called `name`; nullptr for an unknown name.
const ObservationModelEntry* find_observation_model(const std::string& name);

/// The model called `name`. Throws std::invalid_argument naming the known models for an unknown
/// name.
const ObservationModelEntry& observation_model(const std::string& name);

/// Builds the model `config.model` over `map` (which must outlive it) for a sensor with
/// `calibration` (the conic models predict its rings). Throws std::invalid_argument naming the
/// known models for an unknown name.
std::unique_ptr<ObservationModel> make_observation_model(
    const ObservationConfig& config, const maps::PlaneMap& map,
    const sensor::LaserCalibration& calibration);

}  // namespace conicloc::localizer
