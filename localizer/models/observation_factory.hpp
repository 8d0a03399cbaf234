#pragma once
// Observation models by name, with one config struct holding every model's settings.

#include <memory>
#include <string>

#include "localizer/models/conic_beam_model.hpp"
#include "localizer/models/conic_segment_model.hpp"
#include "localizer/models/observation_model.hpp"
#include "localizer/models/point_to_plane_model.hpp"
#include "sensor/laser_calibration.hpp"

namespace conicloc::localizer {

struct ObservationConfig {
  std::string model = "conic-beam";  ///< one of observation_model_names()
  ConicBeamConfig conic_beam;
  ConicSegmentConfig conic_segment;
  PointToPlaneConfig point_to_plane;

  /// Sets the sensor's maximum range (m) in every model (beam selection, mixture, predictor,
  /// culling, segmentation).
  void set_max_range(double max_range_m);
};

/// Builds the model `config.model` over `map` (which must outlive it) for a sensor with
/// `calibration` (the conic models predict its rings). Throws std::invalid_argument naming the
/// known models for an unknown name.
std::unique_ptr<ObservationModel> make_observation_model(
    const ObservationConfig& config, const maps::PlaneMap& map,
    const sensor::LaserCalibration& calibration);

}  // namespace conicloc::localizer
