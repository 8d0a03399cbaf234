#pragma once
// What the LiDAR is: per-laser geometry. Sensor frame S is REP-103 (x forward, y left, z up along
// the spin axis). A beam of laser k at azimuth θ (counter-clockwise from x) is the ray
//   p(r) = (0, 0, o_k) + r·(cos φ_k cos θ, cos φ_k sin θ, sin φ_k)      (DESIGN.md)
// where r = r_raw + d_k is the measured distance plus the laser's range offset.

#include <string>
#include <vector>

namespace conicloc::sensor {

enum class SensorModel { VLP16, PuckLite, PuckHiRes, HDL32E, VLP32C };

/// The range (m) beyond which the sensor returns nothing (the VLP-16's rated 100 m): the one
/// default of every observation model's maximum range (selection, mixture, prediction, culling,
/// segmentation).
inline constexpr double kMaxRange_m = 100.0;

struct Laser {
  double elevation_rad = 0.0;       ///< φ_k, positive up
  double vertical_offset_m = 0.0;   ///< o_k, apex of the laser's cone on the spin axis
  double azimuth_offset_rad = 0.0;  ///< added to the firing azimuth (REP-103 sense); 0 for VLP-16
  int ring = 0;                     ///< rank of the elevation, 0 = lowest
  double range_offset_m = 0.0;      ///< d_k, added to every distance (VeloView distCorrection_)
};

/// Lasers indexed by channel (the order they appear in a data block).
struct LaserCalibration {
  SensorModel model = SensorModel::VLP16;
  std::vector<Laser> lasers;

  int ring_count() const { return static_cast<int>(lasers.size()); }
};

}  // namespace conicloc::sensor
