#include "calib/plane_association.hpp"

#include <cmath>

#include "maps/segment_distance.hpp"

namespace conicloc::calib {

int nearest_polygon(const maps::PlaneMap& map, const maps::PlaneIndex& index,
                    const Eigen::Vector3d& point_map, double gate_m) {
  int best = -1;
  double best_distance = gate_m;
  for (const int candidate : index.within(point_map, gate_m)) {
    const double distance =
        (maps::closest_point(map.polygons[candidate], point_map) - point_map).norm();
    if (distance <= best_distance) {
      best_distance = distance;
      best = candidate;
    }
  }
  return best;
}

bool ray_meets_inside(const maps::PlanarPolygon& polygon, const Eigen::Vector3d& origin,
                      const Eigen::Vector3d& direction, double margin_m) {
  // n·(o + s·d) + c = 0  →  s = −(n·o + c) / (n·d).
  const double along = polygon.plane.normal.dot(direction);
  if (along == 0.0 || std::abs(along) < kMinIncidenceCosine * direction.norm()) return false;
  if (along > 0.0 && !polygon.two_sided) return false;  // its back faces solid, not free space
  const double s = -polygon.plane.signed_distance(origin) / along;
  if (!(s > 0.0)) return false;
  const Eigen::Vector2d uv = polygon.frame.project(origin + s * direction);
  if (!polygon.contains_uv(uv)) return false;
  if (maps::distance_to_ring(polygon.outer_uv, uv) < margin_m) return false;
  for (const auto& hole : polygon.holes_uv) {
    if (maps::distance_to_ring(hole, uv) < margin_m) return false;
  }
  return true;
}

int associated_polygon(const maps::PlaneMap& map, const maps::PlaneIndex& index,
                       const Eigen::Vector3d& origin, const Eigen::Vector3d& point_map,
                       double gate_m, double margin_m) {
  const int polygon = nearest_polygon(map, index, point_map, gate_m);
  if (polygon < 0) return -1;
  return ray_meets_inside(map.polygons[polygon], origin, point_map - origin, margin_m) ? polygon
                                                                                       : -1;
}

}  // namespace conicloc::calib
