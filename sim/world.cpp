#include "sim/world.hpp"

#include <cassert>
#include <cmath>

namespace conicloc::sim {

World::World(std::vector<maps::PlanarPolygon> polygons, std::vector<SurfaceMaterial> materials,
             std::vector<MovingPerson> people)
    : bvh_(std::move(polygons)), materials_(std::move(materials)), people_(std::move(people)) {
  assert(materials_.size() == bvh_.polygons().size());
}

std::optional<WorldHit> World::cast(const Ray& ray, double time_s, double min_range_m,
                                    double max_range_m, int hint) const {
  std::optional<WorldHit> best;
  if (const auto hit = bvh_.nearest_hit(ray, min_range_m, max_range_m, hint)) {
    const auto& polygon = bvh_.polygons()[hit->polygon];
    best = WorldHit{hit->range_m, std::abs(polygon.plane.normal.dot(ray.direction)),
                    materials_[hit->polygon], hit->polygon};
  }
  for (const auto& person : people_) {
    // A person about to walk into the sensor steps aside (the cylinder would enclose the sensor).
    if ((person.position(time_s) - ray.origin.head<2>()).norm() < person.radius_m + 0.3) continue;
    const double bound = best ? best->range_m : max_range_m;
    if (const auto t = intersect_person(person, time_s, ray, min_range_m, bound)) {
      // Incidence on a cylinder: the horizontal part of the ray against the radial normal.
      const Eigen::Vector3d p = ray.origin + *t * ray.direction;
      Eigen::Vector2d radial = p.head<2>() - person.position(time_s);
      const double cos_incidence =
          radial.norm() > 1e-9 ? std::abs(radial.normalized().dot(ray.direction.head<2>())) : 1.0;
      best = WorldHit{*t, cos_incidence, SurfaceMaterial{25.0, SurfaceOrigin::Person}, -1};
    }
  }
  return best;
}

}  // namespace conicloc::sim
