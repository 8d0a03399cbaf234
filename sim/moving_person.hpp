#pragma once
// A person the map does not hold: a vertical cylinder walking back and forth between two points.

#include <Eigen/Core>
#include <optional>

#include "sim/ray_polygon.hpp"

namespace conicloc::sim {

struct MovingPerson {
  Eigen::Vector2d from = Eigen::Vector2d::Zero();  ///< map frame, m
  Eigen::Vector2d to = Eigen::Vector2d::Zero();
  double floor_z = 0.0;  ///< feet, m
  double height_m = 1.75;
  double radius_m = 0.22;
  double speed_mps = 1.0;
  double phase_s = 0.0;  ///< time offset of the walk

  /// Centre of the cylinder at `time_s`: a triangle wave from → to → from (constant speed).
  Eigen::Vector2d position(double time_s) const;
};

/// Nearest crossing of `ray` with the side or top of the person's cylinder at `time_s`, within
/// (min_range_m, max_range_m). Side: |(o + t d)_xy − c|² = r², solved as a quadratic in t.
std::optional<double> intersect_person(const MovingPerson& person, double time_s, const Ray& ray,
                                       double min_range_m, double max_range_m);

/// Same, with the cylinder standing at `centre` (its position() at the instant of the ray).
std::optional<double> intersect_person_at(const MovingPerson& person,
                                          const Eigen::Vector2d& centre, const Ray& ray,
                                          double min_range_m, double max_range_m);

}  // namespace conicloc::sim
