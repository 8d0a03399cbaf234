#include "sim/ray_polygon.hpp"

#include <cmath>

namespace conicloc::sim {

std::optional<double> intersect_polygon(const maps::PlanarPolygon& polygon, const Ray& ray,
                                        double min_range_m, double max_range_m) {
  const Eigen::Vector3d& n = polygon.plane.normal;
  const double denominator = n.dot(ray.direction);
  // A ray within ~1e-12 rad of the plane sees it edge-on: no surface to return from.
  if (std::abs(denominator) < 1e-12) return std::nullopt;
  const double t = -(n.dot(ray.origin) + polygon.plane.offset) / denominator;
  if (!(t > min_range_m && t < max_range_m)) return std::nullopt;
  const Eigen::Vector3d point = ray.origin + t * ray.direction;
  // Cheap reject before the ring test: the crossing must lie in the polygon's bounding box.
  const Eigen::Vector3d& lo = polygon.bounds.min();
  const Eigen::Vector3d& hi = polygon.bounds.max();
  const double slack = 1e-7;
  if ((point.array() < lo.array() - slack).any() || (point.array() > hi.array() + slack).any()) {
    return std::nullopt;
  }
  if (!polygon.contains_uv(polygon.frame.project(point))) return std::nullopt;
  return t;
}

}  // namespace conicloc::sim
