#pragma once
// Ray against one bounded planar polygon (with holes): the simulator's own intersection code,
// independent of the localizer's conic model so that simulated scans check the localizer.

#include <Eigen/Core>
#include <optional>

#include "maps/planar_polygon.hpp"

namespace conicloc::sim {

/// A ray p(t) = origin + t·direction, |direction| = 1, map frame.
struct Ray {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
};

/// Distance along the ray to the point where it crosses the polygon, if that lies in
/// (min_range_m, max_range_m) and inside the outer ring but in no hole (holes are glass or
/// openings: they return nothing). Both faces are hit. A ray parallel to the plane misses.
/// Ray-plane: n·(o + t d) + D = 0  =>  t = −(n·o + D) / (n·d).
std::optional<double> intersect_polygon(const maps::PlanarPolygon& polygon, const Ray& ray,
                                        double min_range_m, double max_range_m);

}  // namespace conicloc::sim
