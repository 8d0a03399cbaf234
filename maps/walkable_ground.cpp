#include "maps/walkable_ground.hpp"

#include <algorithm>

namespace conicloc::maps {

namespace {

// Within 60° of up: floors, ramps and stair flights modelled as slopes, never walls or ceilings.
constexpr double kMinWalkableNormalZ = 0.5;
// An upward surface this close to its cell's top is not stood on (a pillar's top face).
constexpr double kMinHeadroom_m = 1.0;

}  // namespace

bool is_walkable_ground(const PlaneMap& map, int polygon, int cell) {
  if (polygon < 0 || polygon >= static_cast<int>(map.polygons.size()) || cell < 0 ||
      cell >= static_cast<int>(map.cells.size())) {
    return false;
  }
  const PlanarPolygon& surface = map.polygons[static_cast<std::size_t>(polygon)];
  const double n_z = surface.plane.normal.z();
  const double n_z_into_cell = surface.cell == cell ? n_z : -n_z;  // a back face faces with −n
  if (!(n_z_into_cell >= kMinWalkableNormalZ)) return false;
  const Eigen::AlignedBox3d& cell_bounds = map.cells[static_cast<std::size_t>(cell)].bounds;
  return cell_bounds.isEmpty() ||
         surface.bounds.max().z() <= cell_bounds.max().z() - kMinHeadroom_m;
}

bool cell_has_floor(const PlaneMap& map, int cell) {
  if (cell < 0 || cell >= static_cast<int>(map.cells.size())) return false;
  const auto& polygons = map.cells[static_cast<std::size_t>(cell)].polygons;
  return std::any_of(polygons.begin(), polygons.end(),
                     [&](int p) { return is_walkable_ground(map, p, cell); });
}

std::optional<double> ground_height_at(const PlaneMap& map, int cell, double x, double y,
                                       double z_max) {
  if (cell < 0 || cell >= static_cast<int>(map.cells.size())) return std::nullopt;
  const Eigen::Vector2d point(x, y);
  std::optional<double> highest;
  for (const int p : map.cells[static_cast<std::size_t>(cell)].polygons) {
    if (!is_walkable_ground(map, p, cell)) continue;
    const PlanarPolygon& surface = map.polygons[static_cast<std::size_t>(p)];
    if (!ring_contains(plan_view(surface.outer), point)) continue;
    const bool in_hole =
        std::any_of(surface.holes.begin(), surface.holes.end(),
                    [&](const Ring3& hole) { return ring_contains(plan_view(hole), point); });
    if (in_hole) continue;
    const Eigen::Vector3d& n = surface.plane.normal;
    const double z = -(n.x() * x + n.y() * y + surface.plane.offset) / n.z();
    if (z <= z_max && (!highest || z > *highest)) highest = z;
  }
  return highest;
}

}  // namespace conicloc::maps
