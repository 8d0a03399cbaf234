#include "calib/plane_association.hpp"

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

}  // namespace conicloc::calib
