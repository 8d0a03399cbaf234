#include "localizer/models/correlated_terms.hpp"

#include <cmath>

namespace conicloc::localizer {

Surfaces coplanar_surfaces(const maps::PlaneMap& map, double angle_rad, double offset_m) {
  std::vector<int> surface(map.polygons.size(), -1);
  std::vector<std::size_t> representatives;  // one polygon per surface
  const double min_cos = std::cos(angle_rad);
  for (std::size_t p = 0; p < map.polygons.size(); ++p) {
    const maps::Plane& plane = map.polygons[p].plane;
    for (std::size_t s = 0; s < representatives.size(); ++s) {
      const maps::Plane& other = map.polygons[representatives[s]].plane;
      if (plane.normal.dot(other.normal) >= min_cos &&
          std::abs(plane.offset - other.offset) <= offset_m) {
        surface[p] = static_cast<int>(s);
        break;
      }
    }
    if (surface[p] < 0) {
      surface[p] = static_cast<int>(representatives.size());
      representatives.push_back(p);
    }
  }
  return {std::move(surface), representatives.size()};
}

}  // namespace conicloc::localizer
