// The simulator's own ray casting: hand-computed hits, BVH against brute force, people.
#include <gtest/gtest.h>

#include <random>

#include "sim/box_building.hpp"
#include "sim/map_errors.hpp"
#include "sim/moving_person.hpp"
#include "sim/polygon_bvh.hpp"
#include "sim/ray_polygon.hpp"
#include "sim/world.hpp"

namespace conicloc::sim {
namespace {

maps::PlanarPolygon square_with_hole() {
  // 4 m × 4 m at z = 2 (centre (0, 0)), a 1 m × 1 m hole at x, y ∈ [1, 2].
  maps::PlanarPolygon polygon;
  const maps::Ring3 outer = {{-2, -2, 2}, {2, -2, 2}, {2, 2, 2}, {-2, 2, 2}};
  const maps::Ring3 hole = {{1, 1, 2}, {2, 1, 2}, {2, 2, 2}, {1, 2, 2}};
  EXPECT_TRUE(maps::make_planar_polygon(outer, {hole}, polygon));
  return polygon;
}

Ray ray(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) {
  return Ray{origin, direction.normalized()};
}

TEST(SimRayPolygon, HitsPlaneAtHandComputedRange) {
  const auto polygon = square_with_hole();
  // Straight up from the origin: t = 2.
  EXPECT_NEAR(*intersect_polygon(polygon, ray({0, 0, 0}, {0, 0, 1}), 0.0, 100.0), 2.0, 1e-12);
  // 45° in x: crosses z = 2 at x = 2 − 0.5: (1.5, 0, 2)... from (-0.5, 0, 0): t = 2√2.
  EXPECT_NEAR(*intersect_polygon(polygon, ray({-0.5, 0, 0}, {1, 0, 1}), 0.0, 100.0),
              2.0 * std::sqrt(2.0), 1e-12);
  // From above, downward: both faces return.
  EXPECT_NEAR(*intersect_polygon(polygon, ray({0, 0, 5}, {0, 0, -1}), 0.0, 100.0), 3.0, 1e-12);
}

TEST(SimRayPolygon, MissesHolesOutsideParallelBehindAndBeyondRange) {
  const auto polygon = square_with_hole();
  EXPECT_FALSE(intersect_polygon(polygon, ray({1.5, 1.5, 0}, {0, 0, 1}), 0.0, 100.0));  // hole
  EXPECT_FALSE(intersect_polygon(polygon, ray({3, 0, 0}, {0, 0, 1}), 0.0, 100.0));      // outside
  EXPECT_FALSE(intersect_polygon(polygon, ray({0, 0, 2}, {1, 0, 0}), 0.0, 100.0));      // parallel
  EXPECT_FALSE(intersect_polygon(polygon, ray({0, 0, 0}, {0, 0, -1}), 0.0, 100.0));     // behind
  EXPECT_FALSE(intersect_polygon(polygon, ray({0, 0, 0}, {0, 0, 1}), 0.0, 1.99));       // too far
  EXPECT_FALSE(intersect_polygon(polygon, ray({0, 0, 0}, {0, 0, 1}), 2.01, 100.0));     // too near
}

TEST(SimPolygonBvh, NearestHitInBoxBuildingByHand) {
  const auto map = make_box_building();
  const PolygonBvh bvh(map.polygons);
  // From (2, 2, 1) in room A: west wall at 2 m, south wall at 2 m, ceiling at 2 m, floor at 1 m.
  EXPECT_NEAR(bvh.nearest_hit(ray({2, 2, 1}, {-1, 0, 0}), 0.0, 100.0)->range_m, 2.0, 1e-12);
  EXPECT_NEAR(bvh.nearest_hit(ray({2, 2, 1}, {0, 0, -1}), 0.0, 100.0)->range_m, 1.0, 1e-12);
  // East through the door (y = 2, z = 0.5) into room B: the east wall of B at x = 10 → 8 m.
  EXPECT_NEAR(bvh.nearest_hit(ray({2, 2, 0.5}, {1, 0, 0}), 0.0, 100.0)->range_m, 8.0, 1e-12);
  // East above the door (z = 2.5): the shared wall at x = 5 → 3 m.
  EXPECT_NEAR(bvh.nearest_hit(ray({2, 2, 2.5}, {1, 0, 0}), 0.0, 100.0)->range_m, 3.0, 1e-12);
  // Through the door and the window (z = 1.5, y = 2): glass returns nothing.
  EXPECT_FALSE(bvh.nearest_hit(ray({2, 2, 1.5}, {1, 0, 0}), 0.0, 100.0));
}

TEST(SimPolygonBvh, AgreesWithBruteForceOnRandomRays) {
  const auto map = make_box_building();
  const PolygonBvh bvh(map.polygons);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> n(0.0, 1.0);
  int hint = -1;
  for (int i = 0; i < 20000; ++i) {
    const Ray r = ray({10 * u(rng), 4 * u(rng), 3 * u(rng)}, {n(rng), n(rng), n(rng)});
    double brute = std::numeric_limits<double>::infinity();
    for (const auto& polygon : bvh.polygons()) {
      if (const auto t = intersect_polygon(polygon, r, 0.0, 100.0)) brute = std::min(brute, *t);
    }
    const auto hit = bvh.nearest_hit(r, 0.0, 100.0);
    const auto hinted = bvh.nearest_hit(r, 0.0, 100.0, hint);
    ASSERT_EQ(hit.has_value(), std::isfinite(brute)) << i;
    ASSERT_EQ(hinted.has_value(), hit.has_value()) << i;
    if (hit) {
      EXPECT_DOUBLE_EQ(hit->range_m, brute);
      EXPECT_DOUBLE_EQ(hinted->range_m, brute);
      hint = hit->polygon;
    }
  }
}

TEST(SimWorld, PeopleAndWallsAgreeWithBruteForce) {
  // The world skips people that cannot be nearer than the wall already hit; the result must be
  // the nearest of every surface, as if each were tested.
  const auto map = make_box_building();
  std::vector<MovingPerson> people;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 6; ++i) {
    MovingPerson person;
    person.from = {10 * u(rng), 4 * u(rng)};
    person.to = {10 * u(rng), 4 * u(rng)};
    person.phase_s = 3 * u(rng);
    people.push_back(person);
  }
  const World world(map.polygons, std::vector<SurfaceMaterial>(map.polygons.size()), people);
  std::normal_distribution<double> n(0.0, 1.0);
  int people_hits = 0;
  for (int i = 0; i < 20000; ++i) {
    const double time_s = 0.01 * i;
    const Ray r = ray({10 * u(rng), 4 * u(rng), 0.3 + 2 * u(rng)}, {n(rng), n(rng), 0.3 * n(rng)});
    double brute = std::numeric_limits<double>::infinity();
    for (const auto& polygon : world.polygons()) {
      if (const auto t = intersect_polygon(polygon, r, 0.3, 100.0)) brute = std::min(brute, *t);
    }
    bool person_nearest = false;
    for (const auto& person : people) {
      // A person within 0.3 m of the sensor steps aside (World's rule).
      if ((person.position(time_s) - r.origin.head<2>()).norm() < person.radius_m + 0.3) continue;
      if (const auto t = intersect_person(person, time_s, r, 0.3, 100.0); t && *t < brute) {
        brute = *t;
        person_nearest = true;
      }
    }
    const auto hit = world.cast(r, time_s, 0.3, 100.0);
    ASSERT_EQ(hit.has_value(), std::isfinite(brute)) << i;
    if (!hit) continue;
    EXPECT_DOUBLE_EQ(hit->range_m, brute) << i;
    EXPECT_EQ(hit->polygon < 0, person_nearest) << i;
    people_hits += person_nearest ? 1 : 0;
  }
  EXPECT_GT(people_hits, 100);  // the people were in the way often enough to test them
}

TEST(SimMovingPerson, CylinderHitByHand) {
  MovingPerson person;
  person.from = {3.0, 0.0};
  person.to = {3.0, 0.0};
  person.radius_m = 0.25;
  person.height_m = 1.8;
  // Horizontal ray at z = 1 along x: front of the cylinder at x = 2.75.
  EXPECT_NEAR(*intersect_person(person, 0.0, ray({0, 0, 1}, {1, 0, 0}), 0.0, 100.0), 2.75, 1e-12);
  // Above the head: miss. Down onto the head from above: the top disc at z = 1.8.
  EXPECT_FALSE(intersect_person(person, 0.0, ray({0, 0, 2}, {1, 0, 0}), 0.0, 100.0));
  EXPECT_NEAR(*intersect_person(person, 0.0, ray({3, 0, 3}, {0, 0, -1}), 0.0, 100.0), 1.2, 1e-12);
}

TEST(SimMovingPerson, WalksBackAndForthAtItsSpeed) {
  MovingPerson person;
  person.from = {0.0, 0.0};
  person.to = {4.0, 0.0};
  person.speed_mps = 1.0;
  EXPECT_NEAR(person.position(1.0).x(), 1.0, 1e-12);
  EXPECT_NEAR(person.position(4.0).x(), 4.0, 1e-12);
  EXPECT_NEAR(person.position(6.0).x(), 2.0, 1e-12);  // on the way back
  EXPECT_NEAR(person.position(8.0).x(), 0.0, 1e-12);
}

TEST(SimMapErrors, ZeroLeavesTheMapAndSigmaMovesWalls) {
  const auto map = make_box_building();
  std::mt19937_64 rng(3);
  const auto same = perturb_walls(map.polygons, 0.0, rng);
  ASSERT_EQ(same.size(), map.polygons.size());
  for (std::size_t i = 0; i < same.size(); ++i) {
    EXPECT_EQ(same[i].plane.offset, map.polygons[i].plane.offset);
  }
  const auto moved = perturb_walls(map.polygons, 0.05, rng);
  double sum_sq = 0.0;
  int walls = 0;
  for (std::size_t i = 0; i < moved.size(); ++i) {
    const auto& before = map.polygons[i];
    if (before.kind != maps::SurfaceKind::Wall) {
      EXPECT_EQ(moved[i].plane.offset, before.plane.offset);
      continue;
    }
    // Centroid shift along the normal; the tilt keeps the normal within a few degrees.
    const double shift = before.plane.normal.dot(moved[i].centroid - before.centroid);
    sum_sq += shift * shift;
    ++walls;
    EXPECT_GT(moved[i].plane.normal.dot(before.plane.normal), std::cos(0.2));
    EXPECT_EQ(moved[i].holes.size(), before.holes.size());
  }
  ASSERT_EQ(walls, 8);
  EXPECT_GT(std::sqrt(sum_sq / walls), 0.01);
  EXPECT_LT(std::sqrt(sum_sq / walls), 0.15);
}

}  // namespace
}  // namespace conicloc::sim
