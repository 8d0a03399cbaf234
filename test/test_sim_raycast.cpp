// The simulator's own ray casting: hand-computed hits, BVH against brute force, people, the
// sensor's blind zone.
#include <gtest/gtest.h>

#include <array>
#include <optional>
#include <random>

#include "sensor/builtin_calibration.hpp"
#include "sim/box_building.hpp"
#include "sim/map_errors.hpp"
#include "sim/moving_person.hpp"
#include "sim/polygon_bvh.hpp"
#include "sim/ray_polygon.hpp"
#include "sim/vlp16_simulator.hpp"
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

/// Six people walking between random points of the box building's rooms (x ∈ [0, 10], y ∈ [0, 4]).
std::vector<MovingPerson> people_in_the_rooms(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<MovingPerson> people;
  for (int i = 0; i < 6; ++i) {
    MovingPerson person;
    person.from = {10 * u(rng), 4 * u(rng)};
    person.to = {10 * u(rng), 4 * u(rng)};
    person.phase_s = 3 * u(rng);
    people.push_back(person);
  }
  return people;
}

/// Every person of `world` at `time_s`: what the culled snapshots are checked against.
PeopleSnapshot everyone_at(const World& world, double time_s) {
  PeopleSnapshot snapshot;
  for (std::size_t i = 0; i < world.people().size(); ++i) {
    snapshot.index.push_back(i);
    snapshot.centre.push_back(world.people()[i].position(time_s));
  }
  return snapshot;
}

/// The nearest surface or person of `people` along `ray`.
std::optional<WorldHit> cast(const World& world, const Ray& ray, const PeopleSnapshot& people) {
  return world.nearer_person(ray, people, 0.3, 100.0, world.nearest_surface(ray, 0.3, 100.0));
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
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const std::vector<MovingPerson> people = people_in_the_rooms(rng);
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
    const auto hit = cast(world, r, everyone_at(world, time_s));
    ASSERT_EQ(hit.has_value(), std::isfinite(brute)) << i;
    if (!hit) continue;
    EXPECT_DOUBLE_EQ(hit->range_m, brute) << i;
    EXPECT_EQ(hit->polygon < 0, person_nearest) << i;
    people_hits += person_nearest ? 1 : 0;
  }
  EXPECT_GT(people_hits, 100);  // the people were in the way often enough to test them
}

TEST(SimWorld, PeopleInReachOfAFiringMeetTheSameAsEveryone) {
  // A firing's rays are tested only against the people they may reach before their walls: the
  // hits must be those against everyone, and people behind the walls or on a storey above the
  // rays' span must be left out.
  const auto map = make_box_building();
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<MovingPerson> people = people_in_the_rooms(rng);
  MovingPerson upstairs = people.front();  // right above the others, on a floor at 10 m
  upstairs.floor_z = 10.0;
  people.push_back(upstairs);
  MovingPerson outside;  // 40 m beyond the walls, on the same floor
  outside.from = outside.to = {50.0, 2.0};
  people.push_back(outside);
  const World world(map.polygons, std::vector<SurfaceMaterial>(map.polygons.size()), people);
  std::normal_distribution<double> n(0.0, 1.0);
  int people_hits = 0;
  // Rays out of a window or a door may reach them: most do not.
  int upstairs_kept = 0, outside_kept = 0;
  const int firings = 2000;
  for (int firing = 0; firing < firings; ++firing) {
    const double time_s = 0.01 * firing;
    const Eigen::Vector3d origin(10 * u(rng), 4 * u(rng), 0.3 + 2 * u(rng));
    const Eigen::Vector2d heading(n(rng), n(rng));
    std::vector<Ray> rays;
    std::vector<double> reach;
    std::vector<std::optional<WorldHit>> surfaces;
    for (int k = 0; k < 16; ++k) {  // a fan from −15° to +15°, 3 cm of vertical offsets
      const double elevation = (-15.0 + 2.0 * k) * M_PI / 180.0;
      const Eigen::Vector3d direction(heading.x() * std::cos(elevation),
                                      heading.y() * std::cos(elevation),
                                      heading.norm() * std::sin(elevation));
      rays.push_back(ray(origin + Eigen::Vector3d(0, 0, 0.002 * k), direction));
      surfaces.push_back(world.nearest_surface(rays.back(), 0.3, 100.0));
      reach.push_back(surfaces.back() ? surfaces.back()->range_m : 100.0);
    }
    const PeopleSnapshot in_reach = world.people_in_reach(time_s, rays, reach);
    for (const std::size_t index : in_reach.index) {
      upstairs_kept += index == 6 ? 1 : 0;
      outside_kept += index == 7 ? 1 : 0;
    }
    const PeopleSnapshot everyone = everyone_at(world, time_s);
    for (int k = 0; k < 16; ++k) {
      const auto hit = world.nearer_person(rays[k], in_reach, 0.3, 100.0, surfaces[k]);
      const auto expected = cast(world, rays[k], everyone);
      ASSERT_EQ(hit.has_value(), expected.has_value()) << firing << " " << k;
      if (!hit) continue;
      EXPECT_EQ(hit->range_m, expected->range_m) << firing << " " << k;
      EXPECT_EQ(hit->polygon, expected->polygon) << firing << " " << k;
      people_hits += hit->polygon < 0 ? 1 : 0;
    }
  }
  EXPECT_GT(people_hits, 100);  // the people were in the way often enough to test them
  EXPECT_LT(upstairs_kept, firings / 4);
  EXPECT_LT(outside_kept, firings / 4);
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

// A wall 0.2 m in front of the sensor, inside its 0.3 m blind zone, and one 5 m away behind it.
// The near wall stops every beam it meets: the beams that meet it within 0.3 m return nothing
// (a real VLP-16 does not see through a wall it stands against), the others return it.
TEST(SimVlp16, AWallInTheBlindZoneBlocksTheBeam) {
  const auto wall_at = [](double x) {
    maps::PlanarPolygon wall;
    const maps::Ring3 ring = {{x, -20, -20}, {x, 20, -20}, {x, 20, 20}, {x, -20, 20}};
    EXPECT_TRUE(maps::make_planar_polygon(ring, {}, wall));
    return wall;
  };
  const World world({wall_at(0.2), wall_at(5.0)}, std::vector<SurfaceMaterial>(2), {});
  SensorEffects effects;
  effects.range_noise_m = 0.0;
  effects.quantisation_m = 0.0;
  effects.dropout_rate = 0.0;
  effects.elevation_error_deg = 0.0;
  std::mt19937_64 rng(1);
  const Vlp16Simulator sensor(world, sensor::builtin_calibration(sensor::SensorModel::VLP16),
                              SensorConfig{}, effects, rng);
  std::array<int, 16> hints;
  hints.fill(-1);
  SensorStats stats;
  int blocked = 0;
  int near_returns = 0;
  // One turn of the head; the sequences facing the walls within 60° meet the near one within
  // 0.2 / (cos 60° cos 15°) = 0.41 m, the far one beyond 5 m.
  const double turn_s = 2.0 * M_PI / sensor.angular_rate();
  for (double t = 0.0; t < turn_s; t += turn_s / 720.0) {
    const double azimuth = std::remainder(sensor.azimuth_at(t), 2.0 * M_PI);
    if (std::abs(azimuth) > M_PI / 3.0) continue;
    const io::FiringSequence sequence =
        sensor.fire(t, 0.0, Eigen::Isometry3d::Identity(), rng, hints, stats);
    for (int k = 0; k < 16; ++k) {
      const double range_m = sequence.range_m[k];
      EXPECT_LT(range_m, 0.42) << "laser " << k << " saw through the wall at θ " << azimuth;
      if (range_m == 0.0) {
        ++blocked;
      } else {
        EXPECT_GT(range_m, effects.min_range_m);
        ++near_returns;
      }
    }
  }
  EXPECT_GT(blocked, 0);
  EXPECT_GT(near_returns, 0);
  // Head on, every laser meets the near wall at 0.2 / cos φ ≤ 0.21 m: no return at all.
  const io::FiringSequence head_on =
      sensor.fire(0.0, 0.0, Eigen::Isometry3d::Identity(), rng, hints, stats);
  ASSERT_NEAR(std::remainder(head_on.azimuth_rad, 2.0 * M_PI), 0.0, 1e-9);
  for (int k = 0; k < 16; ++k) EXPECT_EQ(head_on.range_m[k], 0.0) << "laser " << k;
  EXPECT_EQ(stats.blind_zone, static_cast<std::uint64_t>(blocked) + 16u);
  EXPECT_EQ(stats.no_surface, 0u);
}

/// A corridor 40 m long, 2 m wide, 3 m high, its floor and ceiling laid in 0.5 m tiles (160
/// polygons), side walls, end walls at x = 0 and 40, and 30 narrow panels across its side
/// y ∈ [0, 0.4]: a fan down it meets many polygons, and a panel may stand in front of the wall
/// a ray hit a firing before.
std::vector<maps::PlanarPolygon> tiled_corridor() {
  std::vector<maps::PlanarPolygon> polygons;
  const auto add = [&](const maps::Ring3& ring) {
    maps::PlanarPolygon polygon;
    EXPECT_TRUE(maps::make_planar_polygon(ring, {}, polygon));
    polygons.push_back(polygon);
  };
  for (int i = 0; i < 80; ++i) {
    const double x0 = 0.5 * i, x1 = x0 + 0.5;
    add({{x0, 0, 0}, {x1, 0, 0}, {x1, 2, 0}, {x0, 2, 0}});  // floor, normal up
    add({{x0, 0, 3}, {x0, 2, 3}, {x1, 2, 3}, {x1, 0, 3}});  // ceiling, normal down
  }
  add({{0, 0, 0}, {0, 0, 3}, {40, 0, 3}, {40, 0, 0}});
  add({{0, 2, 0}, {40, 2, 0}, {40, 2, 3}, {0, 2, 3}});
  add({{40, 0, 0}, {40, 0, 3}, {40, 2, 3}, {40, 2, 0}});
  add({{0, 0, 0}, {0, 2, 0}, {0, 2, 3}, {0, 0, 3}});
  for (int i = 0; i < 30; ++i) {
    const double x = 1.0 + 1.3 * i;
    add({{x, 0, 0}, {x, 0.4, 0}, {x, 0.4, 3}, {x, 0, 3}});
  }
  return polygons;
}

TEST(SimPolygonBvh, AFanSharesItsDescentAndHitsWhatEachRayHitsAlone) {
  // Firings of 16 rays from −15° to +15° sweeping about the corridor's axis, each fan hinted
  // with the last firing's hits as the simulator does: every ray's hit (range and polygon) is the
  // one it finds alone, whether its fan's box holds few polygons or more than kMaxShared (down
  // the corridor: the fan is halved), its hint is nearest, is hit behind a panel, or is missed.
  const PolygonBvh bvh(tiled_corridor());
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::array<int, 16> hints;
  hints.fill(-1);
  int crowded_fans = 0, hinted = 0, hinted_behind = 0, rays_hit = 0;
  const int firings = 3000;
  for (int firing = 0; firing < firings; ++firing) {
    // A sensor walking down the corridor and sweeping ±40° about its axis, now and then facing
    // back or jumping (its hints then miss).
    const double azimuth =
        (firing % 5 == 0 ? M_PI : 0.0) + 40.0 * std::sin(0.05 * firing) * M_PI / 180.0;
    const double x = firing % 7 == 0 ? 0.3 + 39.4 * u(rng) : 0.3 + 39.4 * firing / firings;
    const Eigen::Vector3d origin(x, 0.3 + 1.4 * u(rng), 1.0 + 0.2 * u(rng));
    std::array<Ray, 16> rays;
    Eigen::AlignedBox3d region;
    for (int k = 0; k < 16; ++k) {
      const double elevation = (-15.0 + 2.0 * k) * M_PI / 180.0;
      rays[k] = ray(origin + Eigen::Vector3d(0, 0, 0.002 * k),
                    {std::cos(elevation) * std::cos(azimuth),
                     std::cos(elevation) * std::sin(azimuth), std::sin(elevation)});
    }
    // Every other firing from 0.5 m on (the blind zone of a real sensor).
    const double min_range_m = firing % 2 == 0 ? 0.0 : 0.5;
    std::array<std::optional<PolygonHit>, 16> fan;
    bvh.nearest_hits(rays, min_range_m, 100.0, hints, fan);
    for (int k = 0; k < 16; ++k) {
      const auto alone = bvh.nearest_hit(rays[k], min_range_m, 100.0);
      ASSERT_EQ(fan[k].has_value(), alone.has_value()) << firing << " " << k;
      if (!alone) continue;
      ++rays_hit;
      EXPECT_EQ(fan[k]->range_m, alone->range_m) << firing << " " << k;
      EXPECT_EQ(fan[k]->polygon, alone->polygon) << firing << " " << k;
      if (hints[k] == alone->polygon) ++hinted;
      if (hints[k] >= 0 && hints[k] != alone->polygon &&
          intersect_polygon(bvh.polygons()[hints[k]], rays[k], min_range_m, 100.0)) {
        ++hinted_behind;
      }
      region.extend(rays[k].origin);
      region.extend(rays[k].origin + alone->range_m * rays[k].direction);
      hints[k] = fan[k]->polygon;
    }
    int in_region = 0;
    for (const auto& polygon : bvh.polygons()) in_region += polygon.bounds.intersects(region);
    crowded_fans += in_region > PolygonBvh::kMaxShared ? 1 : 0;
  }
  EXPECT_GT(rays_hit, 15 * firings) << crowded_fans << " " << hinted << " " << rays_hit;
  // All three ways were taken often: crowded fans, hints hit, hints missed.
  EXPECT_GT(crowded_fans, firings / 20);
  EXPECT_GT(hinted, rays_hit / 10);
  EXPECT_LT(hinted, rays_hit * 19 / 20);
  EXPECT_GT(hinted_behind, 100);  // a panel (or the floor) in front of the last hit
}

TEST(SimPolygonBvh, MoreRaysThanAFanHoldsAreCastAsSeveralFans) {
  // 40 rays (an HDL-32's firing and more) from one point, half of them hinted with their own hit:
  // each hit is the one its ray finds alone.
  const PolygonBvh bvh(tiled_corridor());
  const std::size_t n = PolygonBvh::kMaxFan + 8;
  std::vector<Ray> rays;
  std::vector<int> hints;
  for (std::size_t k = 0; k < n; ++k) {
    const double elevation = (-20.0 + k) * M_PI / 180.0;
    rays.push_back(ray({3.0, 1.0, 1.2}, {std::cos(elevation), 0.1, std::sin(elevation)}));
    const auto alone = bvh.nearest_hit(rays.back(), 0.0, 100.0);
    hints.push_back(k % 2 == 0 && alone ? alone->polygon : -1);
  }
  std::vector<std::optional<PolygonHit>> fan(n);
  bvh.nearest_hits(rays, 0.0, 100.0, hints, fan);
  for (std::size_t k = 0; k < n; ++k) {
    const auto alone = bvh.nearest_hit(rays[k], 0.0, 100.0);
    ASSERT_TRUE(alone && fan[k]) << k;
    EXPECT_EQ(fan[k]->range_m, alone->range_m) << k;
    EXPECT_EQ(fan[k]->polygon, alone->polygon) << k;
  }
}

TEST(SimPolygonBvh, PolygonsCrossedAtOneDistanceGiveTheLowerIndexWhateverIsTriedFirst) {
  // A slab of zero thickness: a floor (normal up) and the ceiling below it (normal down) at
  // z = 3, overlapping over x ∈ [5, 10], y ∈ [10, 14] (beside the corridor, which only makes a
  // tree around them); rays from below cross both at the same distance, bit
  // for bit. The hit is the polygon of lower index alone, hinted with the other, and in a fan
  // hinted with the other, for either order of the two in the map.
  const auto square = [](double x0, double x1, bool up) {
    maps::PlanarPolygon polygon;
    const maps::Ring3 ring = up ? maps::Ring3{{x0, 10, 3}, {x1, 10, 3}, {x1, 14, 3}, {x0, 14, 3}}
                                : maps::Ring3{{x0, 10, 3}, {x0, 14, 3}, {x1, 14, 3}, {x1, 10, 3}};
    EXPECT_TRUE(maps::make_planar_polygon(ring, {}, polygon));
    return polygon;
  };
  std::vector<maps::PlanarPolygon> polygons = tiled_corridor();
  const int floor_index = static_cast<int>(polygons.size());
  for (const bool floor_first : {true, false}) {
    std::vector<maps::PlanarPolygon> map = polygons;
    map.push_back(floor_first ? square(0, 10, true) : square(5, 15, false));
    map.push_back(floor_first ? square(5, 15, false) : square(0, 10, true));
    const PolygonBvh bvh(map);
    const int lower = floor_index, higher = floor_index + 1;
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int ties = 0;
    for (int firing = 0; firing < 200; ++firing) {
      const Eigen::Vector3d origin(5.5 + 4 * u(rng), 10.5 + 3 * u(rng), 1.0 + u(rng));
      std::array<Ray, 16> rays;
      for (int k = 0; k < 16; ++k) {
        // Up into the overlap: the crossing at z = 3 lies within x ∈ [5, 10], y ∈ [10, 14].
        const double spread = 0.1 * (k - 7.5) / 7.5;
        rays[k] = ray(origin, {spread, 0.1 * (u(rng) - 0.5), 1.0});
      }
      std::array<int, 16> hints;
      hints.fill(higher);
      std::array<std::optional<PolygonHit>, 16> fan;
      bvh.nearest_hits(rays, 0.0, 100.0, hints, fan);
      for (int k = 0; k < 16; ++k) {
        const auto a = intersect_polygon(map[lower], rays[k], 0.0, 100.0);
        const auto b = intersect_polygon(map[higher], rays[k], 0.0, 100.0);
        if (!a || !b || *a != *b) continue;
        ++ties;
        EXPECT_EQ(bvh.nearest_hit(rays[k], 0.0, 100.0)->polygon, lower) << firing << " " << k;
        EXPECT_EQ(bvh.nearest_hit(rays[k], 0.0, 100.0, higher)->polygon, lower);
        EXPECT_EQ(fan[k]->polygon, lower) << firing << " " << k;
      }
    }
    EXPECT_GT(ties, 1000) << floor_first;  // the slab's two faces do tie
  }
}

}  // namespace
}  // namespace conicloc::sim
