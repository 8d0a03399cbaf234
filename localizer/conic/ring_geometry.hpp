#pragma once
// Per-ring cone geometry of a multi-beam LiDAR (DESIGN.md "Frames and conventions"): ring k is the
// family of rays p(r) = (0, 0, o_k) + r·(cos φ_k cos θ, cos φ_k sin θ, sin φ_k), θ the azimuth.

#include <Eigen/Core>
#include <vector>

#include "sensor/laser_calibration.hpp"

namespace conicloc::localizer {

/// One laser ring, with the trigonometry the conic model needs precomputed.
struct RingGeometry {
  int ring = 0;                    ///< rank of the elevation, 0 = lowest
  int channel = 0;                 ///< index in LaserCalibration::lasers
  double elevation_rad = 0.0;      ///< φ_k, positive up
  double vertical_offset_m = 0.0;  ///< o_k: the cone's apex is (0, 0, o_k) in the sensor frame
  double cos_elevation = 1.0;
  double sin_elevation = 0.0;

  Eigen::Vector3d apex() const { return {0.0, 0.0, vertical_offset_m}; }
  /// Unit direction d_k(θ) of the beam at azimuth θ (radians, counter-clockwise from x).
  Eigen::Vector3d direction(double azimuth_rad) const;
  /// The sensor-frame point at range r along the beam at azimuth θ.
  Eigen::Vector3d point(double azimuth_rad, double range_m) const;
};

RingGeometry make_ring_geometry(double elevation_rad, double vertical_offset_m, int ring = 0,
                                int channel = 0);

/// The rings of a calibration, indexed by ring (lowest elevation first).
std::vector<RingGeometry> ring_geometry(const sensor::LaserCalibration& calibration);

}  // namespace conicloc::localizer
