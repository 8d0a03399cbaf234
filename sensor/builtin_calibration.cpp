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

// Puck Hi-Res (VLP-16 Hi-Res manual, vertical angles and offsets): ±10° in 1.33° steps.
constexpr std::array<double, 16> kPuckHiResElevationDeg = {-10.00, 0.67, -8.67, 2.00, -7.33, 3.33,
                                                           -6.00,  4.67, -4.67, 6.00, -3.33, 7.33,
                                                           -2.00,  8.67, -0.67, 10.00};
constexpr std::array<double, 16> kPuckHiResOffsetMm = {7.4, -0.9, 6.5, -1.8, 5.5, -2.7, 4.6, -3.7,
                                                       3.7, -4.6, 2.7, -5.5, 1.8, -6.5, 0.9, -7.4};

// HDL-32E (HDL-32E manual, laser vertical angles): −30.67° … +10.67°, interleaved; no offsets.
constexpr std::array<double, 32> kHdl32eElevationDeg = {
    -30.67, -9.33,  -29.33, -8.00,  -28.00, -6.67,  -26.67, -5.33,  -25.33, -4.00,  -24.00,
    -2.67,  -22.67, -1.33,  -21.33, 0.00,   -20.00, 1.33,   -18.67, 2.67,   -17.33, 4.00,
    -16.00, 5.33,   -14.67, 6.67,   -13.33, 8.00,   -12.00, 9.33,   -10.67, 10.67};

// VLP-32C (VLP-32C manual, laser angles): elevation and azimuth offset δ (degrees, clockwise like
// Velodyne's azimuth: the laser fires at α + δ), by channel.
constexpr std::array<double, 32> kVlp32cElevationDeg = {
    -25.0,  -1.0,   -1.667, -15.639, -11.31, 0.0,    -0.667, -8.843, -7.254, 0.333,  -0.333,
    -6.148, -5.333, 1.333,  0.667,   -4.0,   -4.667, 1.667,  1.0,    -3.667, -3.333, 3.333,
    2.333,  -2.667, -3.0,   7.0,     4.667,  -2.333, -2.0,   15.0,   10.333, -1.333};
constexpr std::array<double, 32> kVlp32cAzimuthOffsetDeg = {
    1.4, -4.2, 1.4, -1.4, 1.4, -1.4, 4.2, -1.4, 1.4, -4.2, 1.4, -1.4, 4.2, -1.4, 4.2, -1.4,
    1.4, -4.2, 1.4, -4.2, 4.2, -1.4, 1.4, -1.4, 1.4, -1.4, 1.4, -4.2, 4.2, -1.4, 1.4, -1.4};

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

template <std::size_t N>
LaserCalibration make_calibration(SensorModel model, const std::array<double, N>& elevation_deg,
                                  const std::array<double, N>* offset_mm,
                                  const std::array<double, N>* azimuth_offset_deg) {
  LaserCalibration calibration;
  calibration.model = model;
  for (std::size_t k = 0; k < N; ++k) {
    Laser laser;
    laser.elevation_rad = elevation_deg[k] * kDegToRad;
    laser.vertical_offset_m = offset_mm ? (*offset_mm)[k] * 1e-3 : 0.0;
    // δ is clockwise (Velodyne's sense); ours is counter-clockwise: θ = −(α + δ).
    laser.azimuth_offset_rad = azimuth_offset_deg ? -(*azimuth_offset_deg)[k] * kDegToRad : 0.0;
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
      return make_calibration<16>(model, kVlp16ElevationDeg, &kVlp16OffsetMm, nullptr);
    case SensorModel::PuckHiRes:
      return make_calibration<16>(model, kPuckHiResElevationDeg, &kPuckHiResOffsetMm, nullptr);
    case SensorModel::HDL32E:
      return make_calibration<32>(model, kHdl32eElevationDeg, nullptr, nullptr);
    case SensorModel::VLP32C:
      return make_calibration<32>(model, kVlp32cElevationDeg, nullptr, &kVlp32cAzimuthOffsetDeg);
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
