// Trajectories: waypoint files, routes through the navigation graph, speed and turn limits,
// hand-held motion, drifting odometry.
#include <gtest/gtest.h>

#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "io/input_error.hpp"
#include "maps/segment_distance.hpp"
#include "sim/box_building.hpp"
#include "sim/navigation_route.hpp"
#include "sim/odometry_drift.hpp"
#include "sim/trajectory.hpp"
#include "sim/waypoint_file.hpp"

namespace conicloc::sim {
namespace {

double yaw_of(const Eigen::Isometry3d& pose) {
  return std::atan2(pose.linear()(1, 0), pose.linear()(0, 0));
}

TEST(SimWaypointFile, ReadsPointsCommentsAndYaw) {
  std::istringstream in("# route\n1 2\n\n3 4 0.5   # upstairs\n5 6 0 90\n");
  const auto w = read_waypoints(in, "w.txt");
  ASSERT_EQ(w.size(), 3u);
  EXPECT_EQ(w[0].floor_point, Eigen::Vector3d(1, 2, 0));
  EXPECT_EQ(w[1].floor_point, Eigen::Vector3d(3, 4, 0.5));
  EXPECT_FALSE(w[1].yaw_rad);
  EXPECT_NEAR(*w[2].yaw_rad, M_PI / 2, 1e-12);
}

TEST(SimWaypointFile, ErrorsNameFileAndLine) {
  std::istringstream bad_number("1 2\n3 x\n");
  try {
    read_waypoints(bad_number, "w.txt");
    FAIL();
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.file(), "w.txt");
    EXPECT_EQ(e.place(), "line 2");
  }
  std::istringstream too_many("1 2 3 4 5\n");
  EXPECT_THROW(read_waypoints(too_many, "w.txt"), io::InputError);
  std::istringstream only_comments("# nothing\n");
  EXPECT_THROW(read_waypoints(only_comments, "w.txt"), io::InputError);
  std::istringstream nan("1 nan\n");
  EXPECT_THROW(read_waypoints(nan, "w.txt"), io::InputError);
}

TEST(SimTrajectory, RespectsSpeedTurnRateAndEndsAtRest) {
  std::mt19937_64 rng(1);
  TrajectoryConfig config;
  config.speed_mps = 1.2;
  const Trajectory trajectory({{{0, 0, 0}, {}}, {{6, 0, 0}, {}}, {{6, 5, 0}, {}}}, config, rng);
  ASSERT_GT(trajectory.duration_s(), 11.0 / 1.2);
  EXPECT_NEAR(trajectory.speed(0.0), 0.0, 1e-12);
  EXPECT_NEAR(trajectory.speed(trajectory.duration_s()), 0.0, 1e-12);
  EXPECT_NEAR((trajectory.floor_point(trajectory.duration_s()) - Eigen::Vector3d(6, 5, 0)).norm(),
              0.0, 1e-9);
  const double dt = 0.01;
  for (double t = dt; t < trajectory.duration_s(); t += dt) {
    const auto a = trajectory.T_map_sensor(t - dt);
    const auto b = trajectory.T_map_sensor(t);
    EXPECT_LE((b.translation() - a.translation()).norm() / dt, 1.2 + 1e-6) << t;
    const double rate = std::abs(std::remainder(yaw_of(b) - yaw_of(a), 2 * M_PI)) / dt;
    EXPECT_LE(rate, config.yaw_rate_max_radps + 1e-6) << t;
    EXPECT_NEAR(b.translation().z(), 0.8, 1e-12);  // robot: level, fixed height
  }
}

TEST(SimTrajectory, StopsAndTurnsToAWaypointYaw) {
  std::mt19937_64 rng(1);
  const Trajectory trajectory({{{0, 0, 0}, {}}, {{3, 0, 0}, M_PI / 2}, {{3, 3, 0}, {}}}, {}, rng);
  // Somewhere the sensor stands at (3, 0) facing +y (sampled every 5 ms; 0.8 rad/s turns).
  bool found = false;
  for (double t = 0; t < trajectory.duration_s(); t += 0.005) {
    const auto pose = trajectory.T_map_sensor(t);
    if ((pose.translation().head<2>() - Eigen::Vector2d(3, 0)).norm() < 1e-4 &&
        std::abs(yaw_of(pose) - M_PI / 2) < 0.005) {
      found = true;
    }
  }
  EXPECT_TRUE(found);
}

TEST(SimTrajectory, ARouteThatDoublesBackIsTurnedOnTheSpot) {
  // Out 6 cm, then back past the start and on (a route leaving a door cell backwards): a robot
  // stops at the hairpin and turns there; it never moves across its own heading.
  std::mt19937_64 rng(1);
  const Trajectory trajectory(
      {{{0, 0, 0}, {}}, {{-0.06, 0, 0}, {}}, {{0.05, 0, 0}, {}}, {{4, 0.3, 0}, {}}}, {}, rng);
  const double dt = 0.01;
  double largest_slip_rad = 0.0;
  for (double t = dt; t < trajectory.duration_s(); t += dt) {
    const auto a = trajectory.T_map_sensor(t - dt);
    const auto b = trajectory.T_map_sensor(t);
    const Eigen::Vector2d step = (b.translation() - a.translation()).head<2>();
    const double rate = std::abs(std::remainder(yaw_of(b) - yaw_of(a), 2 * M_PI)) / dt;
    EXPECT_LE(rate, TrajectoryConfig{}.yaw_rate_max_radps + 1e-6) << t;
    if (step.norm() / dt < 0.02) continue;  // turning on the spot
    const double slip = std::remainder(std::atan2(step.y(), step.x()) - yaw_of(b), 2 * M_PI);
    largest_slip_rad = std::max(largest_slip_rad, std::abs(slip));
  }
  // Turns on the spot beyond 0.35 rad; the path's own curvature adds a little.
  EXPECT_LT(largest_slip_rad, 0.4);
  EXPECT_NEAR((trajectory.floor_point(trajectory.duration_s()) - Eigen::Vector3d(4, 0.3, 0)).norm(),
              0.0, 1e-9);
}

TEST(SimTrajectory, TheYawRateChangesNoFasterThanTheCarrierCanTurn) {
  // A zig-zag route (its curve bends one way, then at once the other at every waypoint) with a
  // turn on the spot in the middle, and a route that doubles back (crawled, then turned on the
  // spot): the yaw rate changes within the yaw acceleration limit, sampled every 20 ms. Before
  // the limit: 73 rad/s² on the zig-zag.
  TrajectoryConfig config;
  const std::vector<std::vector<Waypoint>> routes = {
      {{{0, 0, 0}, {}},
       {{1.5, 0.5, 0}, {}},
       {{3, -0.5, 0}, {}},
       {{4.5, 0.5, 0}, M_PI},
       {{3, 1.5, 0}, {}},
       {{1.5, 0.5, 0}, {}}},
      {{{0, 0, 0}, {}}, {{-0.06, 0, 0}, {}}, {{0.05, 0, 0}, {}}, {{4, 0.3, 0}, {}}}};
  for (std::size_t r = 0; r < routes.size(); ++r) {
    std::mt19937_64 rng(1);
    const Trajectory trajectory(routes[r], config, rng);
    const double dt = 0.02;
    double previous_rate = 0.0;
    double largest = 0.0;
    double largest_slip_rad = 0.0;  // heading against the direction of travel, while driving
    for (double t = dt; t < trajectory.duration_s() + 0.5; t += dt) {
      const double rate =
          std::remainder(trajectory.yaw(t) - trajectory.yaw(t - dt), 2 * M_PI) / dt;
      largest = std::max(largest, std::abs(rate - previous_rate) / dt);
      previous_rate = rate;
      const Eigen::Vector3d step = trajectory.floor_point(t) - trajectory.floor_point(t - dt);
      if (step.norm() / dt < 0.3) continue;
      const double slip = std::remainder(
          std::atan2(step.y(), step.x()) - trajectory.yaw(t - 0.5 * dt), 2 * M_PI);
      largest_slip_rad = std::max(largest_slip_rad, std::abs(slip));
    }
    EXPECT_LT(largest, 1.05 * config.yaw_acceleration_max_radps2) << "route " << r;
    EXPECT_GT(largest, 0.9 * config.yaw_acceleration_max_radps2) << "route " << r;
    // The limit slows the carrier rather than turning it across its way: 0.02 rad at most here.
    EXPECT_LT(largest_slip_rad, 0.05) << "route " << r;
  }
}

TEST(SimTrajectory, AYawAccelerationLimitMustBePositive) {
  // Zero would never turn (the waypoint yaw below ignored), NaN or infinity no profile at all.
  for (const double alpha : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                             std::numeric_limits<double>::infinity()}) {
    std::mt19937_64 rng(1);
    TrajectoryConfig config;
    config.yaw_acceleration_max_radps2 = alpha;
    EXPECT_THROW(Trajectory({{{0, 0, 0}, {}}, {{3, 0, 0}, M_PI / 2}}, config, rng),
                 std::invalid_argument)
        << alpha;
  }
}

TEST(SimTrajectory, AGapInTheGroundIsCrossedLevel) {
  // The route's nominal floor falls from 0 to -0.5 m (waypoints at a cell's lowest point); the
  // ground is level at 0 but missing for 2 < x < 3 (a notch in the modelled floor).
  std::mt19937_64 rng(1);
  const GroundHeightFunction ground = [](const Eigen::Vector3d& p) -> std::optional<double> {
    if (p.x() > 2.0 && p.x() < 3.0) return std::nullopt;
    return 0.0;
  };
  const Trajectory trajectory({{{0, 0, 0}, {}}, {{5, 0, -0.5}, {}}}, {}, rng, ground);
  int in_gap = 0;
  for (double t = 0.0; t <= trajectory.duration_s(); t += 0.05) {
    const Eigen::Vector3d p = trajectory.T_map_sensor(t).translation();
    EXPECT_NEAR(p.z(), 0.8, 1e-9) << "t " << t << " x " << p.x();
    in_gap += p.x() > 2.0 && p.x() < 3.0 ? 1 : 0;
  }
  EXPECT_GT(in_gap, 5);
}

TEST(SimTrajectory, HandheldBobsAndTiltsALittle) {
  std::mt19937_64 rng(2);
  TrajectoryConfig config;
  config.style = MotionStyle::Handheld;
  const Trajectory trajectory({{{0, 0, 0}, {}}, {{10, 0, 0}, {}}}, config, rng);
  double z_min = 10, z_max = -10, max_tilt = 0;
  for (double t = 0; t < trajectory.duration_s(); t += 0.01) {
    const auto pose = trajectory.T_map_sensor(t);
    z_min = std::min(z_min, pose.translation().z());
    z_max = std::max(z_max, pose.translation().z());
    max_tilt = std::max(max_tilt, std::acos(std::clamp(pose.linear()(2, 2), -1.0, 1.0)));
  }
  EXPECT_GT(z_max - z_min, 0.02);
  EXPECT_LT(z_max - z_min, 0.04);
  EXPECT_GT(max_tilt, 0.2 * M_PI / 180);
  EXPECT_LT(max_tilt, 5.0 * M_PI / 180);
}

TEST(SimNavigationRoute, GoesThroughTheDoorAndStaysInsideTheCells) {
  const auto map = make_box_building();
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    std::mt19937_64 rng(seed);
    RouteConfig config;
    config.length_m = 30.0;
    const auto route = plan_navigation_route(map, config, rng);
    ASSERT_GE(route.edges.size(), 3u);
    const Eigen::Vector3d door(5.0, 2.0, 0.0);
    int door_points = 0;
    for (const auto& w : route.waypoints) door_points += (w.floor_point - door).norm() < 1e-9;
    EXPECT_EQ(door_points, static_cast<int>(route.edges.size()));
    const Trajectory trajectory(route.waypoints, {}, rng);
    EXPECT_GE(trajectory.length_m(), 25.0);
    for (double t = 0; t <= trajectory.duration_s(); t += 0.05) {
      const Eigen::Vector2d p = trajectory.T_map_sensor(t).translation().head<2>();
      bool inside = false;
      for (const auto& cell : map.cells) inside = inside || maps::ring_contains(cell.footprint, p);
      ASSERT_TRUE(inside) << "seed " << seed << " t " << t << " at " << p.transpose();
      // Crossing x = 5 only through the door opening (y in [1.55, 2.45]).
      if (std::abs(p.x() - 5.0) < 0.05) {
        EXPECT_GT(p.y(), 1.55);
        EXPECT_LT(p.y(), 2.45);
      }
    }
  }
}

// A 20 m route from room A's node.
Route route_from_room_a(const maps::PlaneMap& map, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  RouteConfig config;
  config.length_m = 20.0;
  config.start_node = "state-A";
  return plan_navigation_route(map, config, rng);
}

TEST(SimNavigationRoute, NeverWalksThroughAWall) {
  // The edge between the rooms is no door, and the straight line between the nodes (y = 0.5)
  // meets the solid part of the wall (the door hole is at y ∈ [1.55, 2.45]): a model without
  // door openings. The route walks about the start room and never crosses x = 5.
  auto map = make_box_building();
  map.navigation.edges[0].through_door = false;
  for (auto& node : map.navigation.nodes) node.position.y() = 0.5;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const auto route = route_from_room_a(map, seed);
    EXPECT_TRUE(route.edges.empty());
    ASSERT_GE(route.waypoints.size(), 4u);
    double length = 0.0;
    for (std::size_t k = 0; k < route.waypoints.size(); ++k) {
      const Eigen::Vector3d& p = route.waypoints[k].floor_point;
      EXPECT_LT(p.x(), 5.0) << "seed " << seed;
      if (k > 0) length += (p - route.waypoints[k - 1].floor_point).norm();
    }
    EXPECT_GE(length, 20.0);
  }
  // With the nodes in line with the door hole, the same non-door edge is walkable.
  for (auto& node : map.navigation.nodes) node.position.y() = 2.0;
  std::mt19937_64 rng(1);
  RouteConfig config;
  config.length_m = 20.0;
  EXPECT_FALSE(plan_navigation_route(map, config, rng).edges.empty());
}

// A door the model leaves closed: the graph says the rooms meet through a door, but the shared
// wall has no opening. The route never walks through it and stays in room A.
TEST(SimNavigationRoute, NeverWalksThroughAClosedDoor) {
  auto map = make_box_building();
  int closed = 0;
  for (auto& polygon : map.polygons) {
    if (polygon.holes.empty() || std::abs(polygon.centroid.x() - 5.0) > 1e-6) continue;
    maps::PlanarPolygon solid;
    ASSERT_TRUE(maps::make_planar_polygon(polygon.outer, {}, solid));
    solid.kind = polygon.kind;
    solid.cell = polygon.cell;
    polygon = solid;
    ++closed;
  }
  ASSERT_GE(closed, 1);
  ASSERT_TRUE(map.navigation.edges[0].through_door);
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const auto route = route_from_room_a(map, seed);
    EXPECT_TRUE(route.edges.empty()) << "seed " << seed;
    for (const auto& w : route.waypoints) EXPECT_LT(w.floor_point.x(), 5.0) << "seed " << seed;
  }
}

// A body keeps the sensor off the walls (beyond its 0.3 m blind zone). Confined to room A (as
// above: no walkable edge), the route wanders by straight runs; with the clearance every point of
// them stays 0.4 m from room A's walls, without it the runs graze them.
TEST(SimNavigationRoute, WandersClearOfTheWalls) {
  auto map = make_box_building();
  map.navigation.edges[0].through_door = false;
  for (auto& node : map.navigation.nodes) node.position.y() = 0.5;
  // Room A's walls in plan: its footprint's edges but the door (y ∈ [1.55, 2.45] at x = 5).
  const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> walls = {{{0, 0}, {5, 0}},
                                                                          {{5, 0}, {5, 1.55}},
                                                                          {{5, 2.45}, {5, 4}},
                                                                          {{5, 4}, {0, 4}},
                                                                          {{0, 4}, {0, 0}}};
  const auto nearest_wall_m = [&](double clearance_m) {
    double nearest = std::numeric_limits<double>::infinity();
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
      std::mt19937_64 rng(seed);
      RouteConfig config;
      config.length_m = 40.0;
      config.start_node = "state-A";
      config.clearance_m = clearance_m;
      const auto route = plan_navigation_route(map, config, rng);
      EXPECT_GE(route.waypoints.size(), 8u);
      for (std::size_t k = 1; k < route.waypoints.size(); ++k) {
        const Eigen::Vector2d a = route.waypoints[k - 1].floor_point.head<2>();
        const Eigen::Vector2d b = route.waypoints[k].floor_point.head<2>();
        for (double t = 0.0; t <= 1.0; t += 0.01) {
          for (const auto& [from, to] : walls) {
            nearest = std::min(
                nearest, std::sqrt(maps::squared_distance_to_segment(a + t * (b - a), from, to)));
          }
        }
      }
    }
    return nearest;
  };
  EXPECT_GE(nearest_wall_m(0.4), 0.4 - 1e-9);
  EXPECT_LT(nearest_wall_m(0.0), 0.2);
}

TEST(SimNavigationRoute, UnknownStartNodeThrows) {
  const auto map = make_box_building();
  std::mt19937_64 rng(1);
  RouteConfig config;
  config.start_node = "nowhere";
  EXPECT_THROW(plan_navigation_route(map, config, rng), std::invalid_argument);
}

TEST(SimOdometry, StartsAtTruthAndDriftsSlowly) {
  std::mt19937_64 rng(4);
  const Trajectory trajectory({{{0, 0, 0}, {}}, {{10, 0, 0}, {}}, {{10, 8, 0}, {}}}, {}, rng);
  const auto odometry = simulate_odometry(trajectory, trajectory.duration_s(), 100.0, {}, rng);
  ASSERT_GT(odometry.size(), 100u);
  EXPECT_NEAR(odometry.front().time_s, 100.0, 1e-12);
  EXPECT_NEAR(
      (odometry.front().pose.translation() - trajectory.T_map_sensor(0).translation()).norm(), 0.0,
      1e-12);
  const double end_error = (odometry.back().pose.translation() -
                            trajectory.T_map_sensor(trajectory.duration_s()).translation())
                               .norm();
  EXPECT_GT(end_error, 1e-4);  // it drifts...
  EXPECT_LT(end_error, 1.0);   // ...by less than 5 % of the 18 m driven
  // Without errors the dead reckoning follows the truth.
  OdometryConfig exact;
  exact.speed_scale_sigma = exact.speed_noise_mps = exact.yaw_rate_bias_radps = 0.0;
  exact.yaw_rate_bias_walk = exact.yaw_rate_noise_radps = 0.0;
  const auto ideal = simulate_odometry(trajectory, trajectory.duration_s(), 0.0, exact, rng);
  EXPECT_LT((ideal.back().pose.translation() -
             trajectory.T_map_sensor(trajectory.duration_s()).translation())
                .norm(),
            0.02);
}

}  // namespace
}  // namespace conicloc::sim
