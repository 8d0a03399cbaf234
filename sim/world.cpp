#include "sim/world.hpp"

#include <cassert>
#include <cmath>

namespace conicloc::sim {

World::World(std::vector<maps::PlanarPolygon> polygons, std::vector<SurfaceMaterial> materials,
             std::vector<MovingPerson> people)
    : bvh_(std::move(polygons)), materials_(std::move(materials)), people_(std::move(people)) {
  assert(materials_.size() == bvh_.polygons().size());
}

std::vector<Eigen::Vector2d> World::people_at(double time_s) const {
  std::vector<Eigen::Vector2d> centres;
  centres.reserve(people_.size());
  for (const auto& person : people_) centres.push_back(person.position(time_s));
  return centres;
}

std::optional<WorldHit> World::cast(const Ray& ray, double time_s, double min_range_m,
                                    double max_range_m, int hint) const {
  return cast(ray, people_at(time_s), min_range_m, max_range_m, hint);
}

std::optional<WorldHit> World::cast(const Ray& ray, const std::vector<Eigen::Vector2d>& people_xy,
                                    double min_range_m, double max_range_m, int hint) const {
  std::optional<WorldHit> best;
  if (const auto hit = bvh_.nearest_hit(ray, min_range_m, max_range_m, hint)) {
    const auto& polygon = bvh_.polygons()[hit->polygon];
    best = WorldHit{hit->range_m, std::abs(polygon.plane.normal.dot(ray.direction)),
                    materials_[hit->polygon], hit->polygon};
  }
  for (std::size_t i = 0; i < people_.size() && i < people_xy.size(); ++i) {
    const auto& person = people_[i];
    const Eigen::Vector2d& centre = people_xy[i];
    const double bound = best ? best->range_m : max_range_m;
    const double distance_xy = (centre - ray.origin.head<2>()).norm();
    // A person about to walk into the sensor steps aside (the cylinder would enclose the sensor).
    if (distance_xy < person.radius_m + 0.3) continue;
    // Any point of the cylinder lies at least distance_xy − r away horizontally, so at least as
    // far along the ray: nothing nearer than the bound there.
    if (distance_xy - person.radius_m > bound) continue;
    if (const auto t = intersect_person_at(person, centre, ray, min_range_m, bound)) {
      // Incidence on a cylinder: the horizontal part of the ray against the radial normal.
      const Eigen::Vector3d p = ray.origin + *t * ray.direction;
      const Eigen::Vector2d radial = p.head<2>() - centre;
      const double cos_incidence =
          radial.norm() > 1e-9 ? std::abs(radial.normalized().dot(ray.direction.head<2>())) : 1.0;
      best = WorldHit{*t, cos_incidence, SurfaceMaterial{25.0, SurfaceOrigin::Person}, -1};
    }
  }
  return best;
}

}  // namespace conicloc::sim
