#include "calib/plane_association.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "maps/segment_distance.hpp"

namespace conicloc::calib {
namespace {

// Where the ray origin + s·(point − origin) crosses one polygon's plane (s = 1 at the point).
struct Crossing {
  int polygon = -1;
  double s = 0.0;
  bool inside = false;  ///< within the polygon's outer ring and outside its holes
  bool clear = false;   ///< at least the margin from every ring, inside or out
  bool front = false;   ///< from the side the polygon faces (either side of a two-sided one)
};

double distance_to_rings(const maps::PlanarPolygon& polygon, const Eigen::Vector2d& uv) {
  double distance = maps::distance_to_ring(polygon.outer_uv, uv);
  for (const auto& hole : polygon.holes_uv)
    distance = std::min(distance, maps::distance_to_ring(hole, uv));
  return distance;
}

}  // namespace

bool ray_meets_inside(const maps::PlanarPolygon& polygon, const Eigen::Vector3d& origin,
                      const Eigen::Vector3d& direction, double margin_m) {
  // n·(o + s·d) + c = 0  →  s = −(n·o + c) / (n·d).
  const double along = polygon.plane.normal.dot(direction);
  if (along == 0.0 || std::abs(along) < kMinIncidenceCosine * direction.norm()) return false;
  if (along > 0.0 && !polygon.two_sided) return false;  // its back faces solid, not free space
  const double s = -polygon.plane.signed_distance(origin) / along;
  if (!(s > 0.0)) return false;
  const Eigen::Vector2d uv = polygon.frame.project(origin + s * direction);
  return polygon.contains_uv(uv) && distance_to_rings(polygon, uv) >= margin_m;
}

int associated_polygon(const maps::PlaneMap& map, const maps::PlaneIndex& index,
                       const Eigen::Vector3d& origin, const Eigen::Vector3d& point_map,
                       double gate_m, double margin_m) {
  const Eigen::Vector3d direction = point_map - origin;
  const std::vector<int> candidates = index.within(point_map, gate_m);
  std::vector<Crossing> crossings;
  crossings.reserve(candidates.size());  // one allocation per return, not one per growth
  for (const int candidate : candidates) {
    const maps::PlanarPolygon& polygon = map.polygons[candidate];
    const double along = polygon.plane.normal.dot(direction);
    if (along == 0.0) continue;
    const double s = -polygon.plane.signed_distance(origin) / along;
    if (!(s > 0.0)) continue;
    const Eigen::Vector2d uv = polygon.frame.project(origin + s * direction);
    crossings.push_back({candidate, s, polygon.contains_uv(uv),
                         distance_to_rings(polygon, uv) >= margin_m,
                         along < 0.0 || polygon.two_sided});
  }
  const Crossing* first = nullptr;
  for (const Crossing& c : crossings) {
    if (c.inside && c.front && (first == nullptr || c.s < first->s)) first = &c;
  }
  if (first == nullptr) return -1;
  // Before it (or level with it), the ray must pass every other nearby polygon clear of its
  // edges and not through its back: else which surface the return came from turns on how far
  // off the modelled ray is from the true one, a few millimetres at the edge.
  for (const Crossing& c : crossings) {
    if (&c == first || c.s > first->s) continue;
    if (!c.clear || (c.inside && !c.front)) return -1;
  }
  return ray_meets_inside(map.polygons[first->polygon], origin, direction, margin_m)
             ? first->polygon
             : -1;
}

}  // namespace conicloc::calib
