#include "sensor/builtin_calibration.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace conicloc::sensor {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

// VLP-16 / Puck LITE (VLP-16 manual, table 9-1): elevation (deg) and vertical offset (mm) by
// channel. The offset o_k is the height of the laser's apex on the spin axis (z = r sin φ + o_k).
constexpr std::array<double, 16> kVlp16ElevationDeg = {-15, 1, -13, 3,  -11, 5,  -9, 7,
                                                       -7,  9, -5,  11, -3,  13, -1, 15};
constexpr std::array<double, 16> kVlp16OffsetMm = {11.2, -0.7, 9.7, -2.2, 8.1, -3.7, 6.6, -5.1,
                                                   5.1,  -6.6, 3.7, -8.1, 2.2, -9.7, 0.7, -11.2};

// Ranks lasers by elevation: ring 0 is the lowest beam.
void assign_rings(LaserCalibration& calibration) {
  std::vector<int> order(calibration.lasers.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return calibration.lasers[a].elevation_rad < calibration.lasers[b].elevation_rad;
  });
  for (std::size_t rank = 0; rank < order.size(); ++rank) {
    calibration.lasers[order[rank]].ring = static_cast<int>(rank);
  }
}

LaserCalibration vlp16_family(SensorModel model) {
  LaserCalibration calibration;
  calibration.model = model;
  for (std::size_t k = 0; k < kVlp16ElevationDeg.size(); ++k) {
    Laser laser;
    laser.elevation_rad = kVlp16ElevationDeg[k] * kDegToRad;
    laser.vertical_offset_m = kVlp16OffsetMm[k] * 1e-3;
    calibration.lasers.push_back(laser);
  }
  assign_rings(calibration);
  return calibration;
}

}  // namespace

LaserCalibration builtin_calibration(SensorModel model) {
  switch (model) {
    case SensorModel::VLP16:
    case SensorModel::PuckLite:
      return vlp16_family(model);
    default:
      break;
  }
  throw std::invalid_argument("no built-in calibration for sensor model " +
                              sensor_model_name(model));
}

std::optional<SensorModel> parse_sensor_model(const std::string& name) {
  if (name == "vlp16") return SensorModel::VLP16;
  if (name == "puck-lite") return SensorModel::PuckLite;
  if (name == "puck-hires") return SensorModel::PuckHiRes;
  if (name == "hdl32e") return SensorModel::HDL32E;
  if (name == "vlp32c") return SensorModel::VLP32C;
  return std::nullopt;
}

std::string sensor_model_name(SensorModel model) {
  switch (model) {
    case SensorModel::VLP16:
      return "vlp16";
    case SensorModel::PuckLite:
      return "puck-lite";
    case SensorModel::PuckHiRes:
      return "puck-hires";
    case SensorModel::HDL32E:
      return "hdl32e";
    case SensorModel::VLP32C:
      return "vlp32c";
  }
  return "vlp16";
}

}  // namespace conicloc::sensor
