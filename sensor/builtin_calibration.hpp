#pragma once
// Factory calibration tables, per model, from the sensors' manuals.

#include <optional>
#include <string>

#include "sensor/laser_calibration.hpp"

namespace conicloc::sensor {

/// The built-in calibration of a model (elevation and vertical offset per channel, rings ranked).
LaserCalibration builtin_calibration(SensorModel model);

/// "vlp16", "puck-lite", "puck-hires", "hdl32e", "vlp32c" -> model; nullopt for anything else.
std::optional<SensorModel> parse_sensor_model(const std::string& name);

/// The name parse_sensor_model() accepts for `model`.
std::string sensor_model_name(SensorModel model);

}  // namespace conicloc::sensor
