#pragma once
// Which of a laser's four corrections its returns can measure. Point-to-plane residuals only see
// a correction through the plane normals the laser hits:
//   vertical offset Δo moves points along the spin axis: invisible on a wall parallel to it, it
//     needs a plane with |n_z| ≥ min_normal_component in the sensor frame: a floor, ceiling or
//     slope, or a wall seen by a sensor tilted by 3° or more (|n_z| = sin β). Held at 0 there
//     instead, its error went into the elevation of a near-level laser: on a wall at ρ, a tilt β
//     gives both the same range change with the azimuth, Δo·sin β and ρ·sin β·Δφ (0.12° for a
//     laser at +1° in one seed; 0.02° once fitted);
//   azimuth offset Δψ turns the scan line about the spin axis: invisible on a level floor or
//     ceiling, it needs walls (|n_xy| large);
//   elevation, range and vertical offset separate only when the laser sees planes in different
//     directions (on one plane family they move points alike); and a floor or ceiling seen at
//     one range (a level sensor on a flat floor) measures only o + r·sin φ: Δo then goes with
//     Δφ, and the vertical offset is flagged (held at its decode value; the elevation absorbs it).
// So a laser seeing fewer than two planes, or only parallel ones, gives no number at all; and
// the information block of its corrections, scaled to unit diagonal, flags what is left
// rank-deficient.

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

namespace conicloc::calib {

struct ObservabilityConfig {
  int min_plane_returns = 20;           ///< a plane counts when the laser has this many on it
  double parallel_deg = 10.0;           ///< normals closer than this are one direction
  double min_normal_component = 0.05;   ///< |n_z| for Δo, |n_xy| for Δψ
  double min_scaled_eigenvalue = 1e-6;  ///< of the unit-diagonal information block
  double min_range_spread = 0.05;       ///< std/mean of the ranges on floor-like planes, for Δo
};

/// What one laser saw: its returns per plane, the plane normals in the sensor frame.
struct LaserView {
  std::vector<Eigen::Vector3d> normals_sensor;  ///< one per plane with enough returns
  int planes_seen = 0;                          ///< planes with any return
  int returns = 0;
  double floor_range_mean_m = 0.0;  ///< of its returns on planes with |n_z| ≥ min_normal_component
  double floor_range_sd_m = 0.0;
  Eigen::Matrix4d information = Eigen::Matrix4d::Zero();  ///< JᵀWJ of (Δφ, Δo, Δψ, Δd)
};

struct LaserObservability {
  std::array<bool, 4> observable{};  ///< Δφ, Δo, Δψ, Δd
  std::string missing;               ///< what is missing, empty when all four are observable

  bool all() const { return observable[0] && observable[1] && observable[2] && observable[3]; }
};

LaserObservability laser_observability(const LaserView& view, const ObservabilityConfig& config);

}  // namespace conicloc::calib
