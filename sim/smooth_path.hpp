#pragma once
// A smooth curve through waypoints: centripetal Catmull-Rom (Yury, Schaefer & Warren 2011: knot
// spacing |P_{i+1} − P_i|^½, no cusps or self-intersections), sampled densely by arc length.

#include <Eigen/Core>
#include <vector>

namespace conicloc::sim {

struct PathSample {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double s_m = 0.0;          ///< arc length from the start
  double heading_rad = 0.0;  ///< direction of travel in the xy plane
  double curvature = 0.0;    ///< dheading/ds, 1/m (horizontal; > 0 turning left)
};

/// Samples the curve through `waypoints` (consecutive duplicates dropped) every ≤ `step_m`.
/// One waypoint gives one sample; the curve passes through every waypoint.
std::vector<PathSample> smooth_path(const std::vector<Eigen::Vector3d>& waypoints,
                                    double step_m = 0.05);

}  // namespace conicloc::sim
