#include "sim/world.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>

namespace conicloc::sim {

World::World(std::vector<maps::PlanarPolygon> polygons, std::vector<SurfaceMaterial> materials,
             std::vector<MovingPerson> people)
    : bvh_(std::move(polygons)), materials_(std::move(materials)), people_(std::move(people)) {
  assert(materials_.size() == bvh_.polygons().size());
  std::vector<Eigen::AlignedBox2d> walks;
  for (const MovingPerson& person : people_) {
    paths_.emplace_back(person.from.cwiseMin(person.to), person.from.cwiseMax(person.to));
    walks.emplace_back(paths_.back().min().array() - person.radius_m,
                       paths_.back().max().array() + person.radius_m);
  }
  people_grid_ = PeopleGrid(walks);
}

PeopleSnapshot World::people_in_reach(double time_s, std::span<const Ray> rays,
                                      std::span<const double> reach_m) const {
  assert(rays.size() == reach_m.size());
  PeopleSnapshot snapshot;
  if (rays.empty() || people_.empty()) return snapshot;
  // The rays' heights before their surfaces, the farthest reach, and how far apart their origins
  // stand horizontally (a laser's vertical offset, tilted): the horizontal test is made from
  // the first origin, widened by that.
  double z_low = std::numeric_limits<double>::infinity(), z_high = -z_low;
  double reach = 0.0, origin_spread = 0.0;
  for (std::size_t k = 0; k < rays.size(); ++k) {
    const double z_end = rays[k].origin.z() + reach_m[k] * rays[k].direction.z();
    z_low = std::min({z_low, rays[k].origin.z(), z_end});
    z_high = std::max({z_high, rays[k].origin.z(), z_end});
    reach = std::max(reach, reach_m[k]);
    origin_spread = std::max(
        origin_spread, (rays[k].origin.head<2>() - rays.front().origin.head<2>()).norm());
  }
  const Eigen::Vector2d origin = rays.front().origin.head<2>();
  // Any point of the cylinder a ray meets lies at least |c − o| − r from its origin
  // horizontally, so at least as far along the ray: only people whose walks (widened by their
  // radii) come within reach + spread of o can be met. Sorted into the order of people_, in
  // which nearer_person keeps the first of two people at one range.
  std::vector<std::pair<std::size_t, Eigen::Vector2d>> near;
  people_grid_.for_each_near(origin, reach + origin_spread, [&](std::size_t i) {
    const MovingPerson& person = people_[i];
    if (person.floor_z > z_high || person.floor_z + person.height_m < z_low) return;
    // |c − o| is at least the distance from o to the box of the centre's walk, which spares
    // the position of those far away.
    const double farthest = reach + person.radius_m + origin_spread;
    if (paths_[i].squaredExteriorDistance(origin) > farthest * farthest) return;
    const Eigen::Vector2d centre = person.position(time_s);
    if ((centre - origin).squaredNorm() > farthest * farthest) return;
    near.emplace_back(i, centre);
  });
  std::sort(near.begin(), near.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  snapshot.index.reserve(near.size());
  snapshot.centre.reserve(near.size());
  for (const auto& [i, centre] : near) {
    snapshot.index.push_back(i);
    snapshot.centre.push_back(centre);
  }
  return snapshot;
}

std::optional<WorldHit> World::nearest_surface(const Ray& ray, double min_range_m,
                                               double max_range_m, int hint) const {
  const auto hit = bvh_.nearest_hit(ray, min_range_m, max_range_m, hint);
  if (!hit) return std::nullopt;
  return world_hit(ray, *hit);
}

void World::nearest_surfaces(std::span<const Ray> rays, double min_range_m, double max_range_m,
                             std::span<const int> hints,
                             std::span<std::optional<WorldHit>> out) const {
  assert(hints.size() == rays.size() && out.size() == rays.size());
  constexpr std::size_t kFan = PolygonBvh::kMaxFan;
  std::array<std::optional<PolygonHit>, kFan> hits;
  for (std::size_t first = 0; first < rays.size(); first += kFan) {
    const std::size_t n = std::min(kFan, rays.size() - first);
    bvh_.nearest_hits(rays.subspan(first, n), min_range_m, max_range_m, hints.subspan(first, n),
                      std::span<std::optional<PolygonHit>>(hits.data(), n));
    for (std::size_t k = 0; k < n; ++k) {
      out[first + k] = hits[k] ? std::optional(world_hit(rays[first + k], *hits[k])) : std::nullopt;
    }
  }
}

WorldHit World::world_hit(const Ray& ray, const PolygonHit& hit) const {
  const auto& polygon = bvh_.polygons()[hit.polygon];
  return WorldHit{hit.range_m, std::abs(polygon.plane.normal.dot(ray.direction)),
                  materials_[hit.polygon], hit.polygon};
}

std::optional<WorldHit> World::nearer_person(const Ray& ray, const PeopleSnapshot& people,
                                             double min_range_m, double max_range_m,
                                             std::optional<WorldHit> surface) const {
  std::optional<WorldHit> best = std::move(surface);
  for (std::size_t j = 0; j < people.index.size(); ++j) {
    const MovingPerson& person = people_[people.index[j]];
    const Eigen::Vector2d& centre = people.centre[j];
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
