#include "sim/clutter.hpp"

#include <algorithm>
#include <cmath>

namespace conicloc::sim {
namespace {

// Horizontal distance from `point` to the nearest path point on the same storey (within 2.5 m z).
double distance_to_path(const std::vector<Eigen::Vector3d>& path, const Eigen::Vector2d& point,
                        double floor_z) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& p : path) {
    if (p.z() < floor_z - 0.5 || p.z() > floor_z + 2.5) continue;
    best = std::min(best, (p.head<2>() - point).norm());
  }
  return best;
}

// The segment a→b stays inside the footprint (sampled every 10 cm).
bool segment_inside(const maps::Ring2& footprint, const Eigen::Vector2d& a,
                    const Eigen::Vector2d& b) {
  const int steps = std::max(1, static_cast<int>((b - a).norm() / 0.1));
  for (int i = 0; i <= steps; ++i) {
    if (!maps::ring_contains(footprint, a + (b - a) * (static_cast<double>(i) / steps))) {
      return false;
    }
  }
  return true;
}

void add_box(Clutter& clutter, const Eigen::Vector2d& centre, double yaw, double width,
             double depth, double floor_z, double height, double reflectivity) {
  const Eigen::Rotation2Dd rotation(yaw);
  std::array<Eigen::Vector3d, 4> bottom;
  std::array<Eigen::Vector3d, 4> top;
  const std::array<Eigen::Vector2d, 4> corners = {
      Eigen::Vector2d(-width / 2, -depth / 2), Eigen::Vector2d(width / 2, -depth / 2),
      Eigen::Vector2d(width / 2, depth / 2), Eigen::Vector2d(-width / 2, depth / 2)};
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector2d c = centre + rotation * corners[i];
    bottom[i] = {c.x(), c.y(), floor_z};
    top[i] = {c.x(), c.y(), floor_z + height};
  }
  std::vector<maps::Ring3> faces;
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    faces.push_back({bottom[i], bottom[j], top[j], top[i]});  // outward normal
  }
  faces.push_back({top[0], top[1], top[2], top[3]});
  for (const auto& face : faces) {
    maps::PlanarPolygon polygon;
    if (!maps::make_planar_polygon(face, {}, polygon)) continue;
    polygon.source_id = "clutter-box-" + std::to_string(clutter.boxes);
    clutter.polygons.push_back(std::move(polygon));
    clutter.materials.push_back({reflectivity, SurfaceOrigin::Furniture});
  }
  ++clutter.boxes;
}

}  // namespace

Clutter make_clutter(const maps::PlaneMap& map, const std::vector<Eigen::Vector3d>& path,
                     const ClutterConfig& config, std::mt19937_64& rng) {
  Clutter clutter;
  if (config.level <= 0) return clutter;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * unit(rng); };
  for (const auto& cell : map.cells) {
    if (!cell.navigable || cell.footprint.size() < 3) continue;
    const double area = std::abs(maps::signed_area(cell.footprint));
    Eigen::AlignedBox2d box;
    for (const auto& p : cell.footprint) box.extend(p);
    auto random_point = [&] {
      return Eigen::Vector2d(uniform(box.min().x(), box.max().x()),
                             uniform(box.min().y(), box.max().y()));
    };
    const double headroom = cell.ceiling_z - cell.floor_z;
    // Expected counts rounded stochastically, so small rooms get clutter now and then.
    const double box_count = config.level * area / 25.0;
    const int boxes = static_cast<int>(box_count) + (unit(rng) < box_count - std::floor(box_count));
    for (int placed = 0, tries = 0; placed < boxes && tries < 50 * boxes; ++tries) {
      const Eigen::Vector2d centre = random_point();
      const double yaw = uniform(-M_PI, M_PI);
      const double width = uniform(0.4, 1.6);
      const double depth = uniform(0.4, 0.9);
      const double height = std::min(uniform(0.4, 1.8), 0.8 * headroom);
      const Eigen::Rotation2Dd rotation(yaw);
      bool inside = true;
      for (const double sx : {-0.5, 0.5}) {
        for (const double sy : {-0.5, 0.5}) {
          inside = inside &&
                   maps::ring_contains(cell.footprint,
                                       centre + rotation * Eigen::Vector2d(sx * width, sy * depth));
        }
      }
      const double half_diagonal = 0.5 * std::hypot(width, depth);
      if (!inside ||
          distance_to_path(path, centre, cell.floor_z) < config.clearance_m + half_diagonal) {
        continue;
      }
      add_box(clutter, centre, yaw, width, depth, cell.floor_z, height, uniform(10.0, 90.0));
      ++placed;
    }
    const double person_count = config.level * area / 60.0;
    const int people =
        static_cast<int>(person_count) + (unit(rng) < person_count - std::floor(person_count));
    for (int placed = 0, tries = 0; placed < people && tries < 50 * people; ++tries) {
      MovingPerson person;
      person.from = random_point();
      person.to = random_point();
      person.floor_z = cell.floor_z;
      person.height_m = std::min(uniform(1.55, 1.95), 0.95 * headroom);
      person.radius_m = uniform(0.18, 0.26);
      person.speed_mps = uniform(0.6, 1.4);
      person.phase_s = uniform(0.0, 100.0);
      if (!segment_inside(cell.footprint, person.from, person.to)) continue;
      clutter.people.push_back(person);
      ++placed;
    }
  }
  return clutter;
}

}  // namespace conicloc::sim
