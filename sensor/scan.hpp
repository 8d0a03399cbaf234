#pragma once
// What the LiDAR measures: one full rotation as per-ring scan lines (the paper's m × n matrix).

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "sensor/laser_calibration.hpp"

namespace conicloc::sensor {

enum class ReturnStatus : std::uint8_t {
  Valid,       ///< a range was measured
  NoReturn,    ///< the sensor reported distance 0 (kept so a ring keeps its shape)
  OutOfRange,  ///< beyond the configured maximum range
};

enum class ReturnKind : std::uint8_t { Strongest, Last, Dual };  // Dual: second return of a pair

/// One return of one firing of one laser.
struct Return {
  double azimuth_rad = 0.0;  ///< θ, counter-clockwise from x (REP-103), in [0, 2π)
  double range_m = 0.0;      ///< along the beam from the laser's apex (0, 0, o_k)
  double time_s = 0.0;       ///< firing time, device clock unwrapped (monotonic), seconds
  std::uint8_t intensity = 0;
  ReturnStatus status = ReturnStatus::Valid;
  ReturnKind kind = ReturnKind::Strongest;
};

/// One laser's scan line over a rotation, sorted by azimuth.
struct RingScan {
  int ring = 0;  ///< 0 = lowest elevation
  int channel = 0;
  double elevation_rad = 0.0;
  double vertical_offset_m = 0.0;
  std::vector<Return> returns;
};

struct Scan {
  std::size_t index = 0;
  double start_time_s = 0.0;
  double end_time_s = 0.0;
  bool partial = false;         ///< the first or last rotation of a capture, cut short
  std::vector<RingScan> rings;  ///< indexed by ring

  std::size_t valid_returns() const;
};

/// A scan with one empty ring per laser of `calibration`, indexed by ring, each ring's channel,
/// elevation and vertical offset set from its laser.
Scan empty_scan(const LaserCalibration& calibration);

/// Sorts every ring of `scan` by azimuth and sets its start and end time to its earliest and
/// latest return's. Returns false (times untouched) when the scan holds no return.
bool sort_rings_and_time(Scan& scan);

/// The sensor-frame point of a return: (0, 0, o_k) + r·d_k(θ).
Eigen::Vector3d sensor_point(const RingScan& ring, const Return& ret);
/// The same with the ring's cos and sin of its elevation given (taken once per ring).
Eigen::Vector3d sensor_point(const RingScan& ring, const Return& ret, double cos_elevation,
                             double sin_elevation);

/// All valid returns as sensor-frame points (3 × N), ring by ring.
Eigen::Matrix3Xd sensor_points(const Scan& scan);

}  // namespace conicloc::sensor
