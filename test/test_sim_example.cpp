// The simulator on the shipped example building (two storeys, stairs, doors, a slanted facade).
#include <gtest/gtest.h>

#include <filesystem>

#include "io/indoorgml.hpp"
#include "io/pcap_reader.hpp"
#include "io/pcap_writer.hpp"
#include "io/velodyne_decoder.hpp"
#include "sensor/builtin_calibration.hpp"
#include "sim/navigation_geometry.hpp"
#include "sim/navigation_route.hpp"
#include "sim/simulation.hpp"
#include "test/temp_path.hpp"

namespace conicloc::sim {
namespace {

class SimExample : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::filesystem::exists(CONICLOC_EXAMPLE_MAP)) GTEST_SKIP() << "no example building";
    map_ = io::load_indoorgml(CONICLOC_EXAMPLE_MAP).map;
  }
  maps::PlaneMap map_;
};

// Index of a navigable cell holding the floor point (xy in the footprint, z within the cell).
int cell_at(const maps::PlaneMap& map, const Eigen::Vector3d& floor_point) {
  for (int c = 0; c < static_cast<int>(map.cells.size()); ++c) {
    const auto& cell = map.cells[c];
    if (!cell.navigable || cell.footprint.size() < 3) continue;
    if (floor_point.z() < cell.floor_z - 0.05 || floor_point.z() > cell.ceiling_z) continue;
    if (maps::ring_contains(cell.footprint, floor_point.head<2>())) return c;
    // A staircase (spanning storeys): its footprint may cover only the flight; the landings lie
    // within its bounds.
    const bool spans_storeys = cell.ceiling_z - cell.floor_z > 4.0;
    const Eigen::Vector2d lo = cell.bounds.min().head<2>();
    const Eigen::Vector2d hi = cell.bounds.max().head<2>();
    if (spans_storeys && (floor_point.head<2>().array() >= lo.array()).all() &&
        (floor_point.head<2>().array() <= hi.array()).all()) {
      return c;
    }
  }
  return -1;
}

TEST_F(SimExample, RoutesStayInNavigableCellsThroughDoorsAcrossStoreys) {
  const auto map = with_navigation_geometry(map_);
  bool upstairs = false;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    std::mt19937_64 rng(seed);
    RouteConfig config;
    config.length_m = 120.0;
    const auto route = plan_navigation_route(map, config, rng);
    ASSERT_GE(route.edges.size(), 4u);
    for (const int e : route.edges) {
      const auto& edge = map.navigation.edges[e];
      // Every edge taken passes its door point (at floor level).
      bool passed = false;
      for (const auto& w : route.waypoints) {
        passed = passed || (w.floor_point.head<2>() - edge.door_point.head<2>()).norm() < 1e-9;
      }
      EXPECT_TRUE(passed) << edge.id;
    }
    const Trajectory trajectory(route.waypoints, {}, rng);
    // Near a door the path crosses the boundary between two footprints (or a footprint that
    // stops short of its door): points within 0.35 m of a door taken count as in the doorway.
    auto in_doorway = [&](const Eigen::Vector3d& p) {
      for (const int e : route.edges) {
        const auto& door = map.navigation.edges[e].door_point;
        if ((p.head<2>() - door.head<2>()).norm() < 0.35) return true;
      }
      return false;
    };
    for (double t = 0; t <= trajectory.duration_s(); t += 0.1) {
      const Eigen::Vector3d p = trajectory.floor_point(t);
      if (in_doorway(p)) continue;
      ASSERT_GE(cell_at(map, p), 0) << "seed " << seed << " t " << t << " at " << p.transpose();
      upstairs = upstairs || p.z() > 3.0;
    }
  }
  EXPECT_TRUE(upstairs);  // some route climbs the stairs
}

TEST_F(SimExample, PointsLieOnTheMapWithTheConfiguredNoise) {
  SimulationConfig config;
  config.duration_s = 1.0;
  config.disable_effects();
  config.effects.range_noise_m = 0.03;
  config.seed = 3;
  Simulation simulation(map_, config);
  const std::string path =
      conicloc::test::unique_temp_path("sim_example.pcap").string();
  SimulationStats stats;
  {
    io::PcapWriter writer(path);
    stats = simulation.run([&](const io::EncodedPacket& packet, double utc) {
      writer.write_udp(packet.payload, utc);
    });
  }
  io::PcapReader reader(path, {2368});
  io::VelodyneDecoder decoder(sensor::builtin_calibration(sensor::SensorModel::VLP16));
  std::vector<io::DecodedPoint> points;
  double sum_sq = 0.0;
  std::size_t on = 0, off = 0, valid = 0;
  while (auto datagram = reader.next()) {
    points.clear();
    decoder.decode(datagram->payload, datagram->capture_time_s - config.start_epoch_s, points);
    for (const auto& point : points) {
      if (point.range_m <= 0.0f) continue;
      ++valid;
      const Eigen::Vector3d p = simulation.trajectory().T_map_sensor(point.time_s) *
                                Eigen::Vector3d(point.x_m, point.y_m, point.z_m);
      double best = std::numeric_limits<double>::infinity();
      for (const auto& polygon : map_.polygons) {
        Eigen::AlignedBox3d box = polygon.bounds;
        box.min().array() -= 0.25;
        box.max().array() += 0.25;
        if (box.contains(p)) best = std::min(best, std::abs(polygon.plane.signed_distance(p)));
      }
      if (best > 0.2) {
        ++off;
      } else {
        sum_sq += best * best;
        ++on;
      }
    }
  }
  std::filesystem::remove(path);
  EXPECT_EQ(valid, stats.sensor.map_hits);
  ASSERT_GT(on, 100000u);
  EXPECT_NEAR(std::sqrt(sum_sq / on), 0.03, 0.2 * 0.03);
  EXPECT_LT(static_cast<double>(off), 1e-3 * valid);
}

}  // namespace
}  // namespace conicloc::sim
