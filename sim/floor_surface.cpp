#include "sim/floor_surface.hpp"

#include <utility>

namespace conicloc::sim {
namespace {

constexpr double kMinWalkableNormalZ = 0.5;  // cos 60°: a 37° stair flight has n_z = 0.8

std::vector<maps::PlanarPolygon> walkable(const std::vector<maps::PlanarPolygon>& polygons) {
  std::vector<maps::PlanarPolygon> out;
  for (const auto& polygon : polygons) {
    const double n_z = polygon.plane.normal.z();
    if (n_z >= kMinWalkableNormalZ || (polygon.two_sided && -n_z >= kMinWalkableNormalZ)) {
      out.push_back(polygon);
    }
  }
  return out;
}

}  // namespace

FloorSurface::FloorSurface(const std::vector<maps::PlanarPolygon>& polygons)
    : bvh_(walkable(polygons)) {}

std::optional<double> FloorSurface::height_under(const Eigen::Vector3d& near_point,
                                                 double search_up_m, double search_down_m) const {
  if (bvh_.polygons().empty()) return std::nullopt;
  Ray down;
  down.origin = near_point + Eigen::Vector3d(0.0, 0.0, search_up_m);
  down.direction = -Eigen::Vector3d::UnitZ();
  // The nearest hit going down is the highest walkable surface below the search start.
  const auto hit = bvh_.nearest_hit(down, 0.0, search_up_m + search_down_m);
  if (!hit) return std::nullopt;
  return down.origin.z() - hit->range_m;
}

}  // namespace conicloc::sim
