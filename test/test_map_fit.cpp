// The pose a map gives a scan (sim/map_fit.hpp): the truth where the world is the map; where every
// wall stands off by one translation t, the truth moved by −t (each residual is 0 there); along a
// direction the returns do not fix, the truth.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "sim/map_fit.hpp"
#include "synthetic_room.hpp"

namespace sim = conicloc::sim;
namespace maps = conicloc::maps;
namespace ct = conicloc::test;

namespace {

maps::Ring3 moved(const maps::Ring3& ring, const Eigen::Vector3d& t) {
  maps::Ring3 out;
  for (const auto& p : ring) out.push_back(p + t);
  return out;
}

// The world of `map` with every wall moved by `t`, and a box the map lacks in it.
sim::World world_with_walls_moved(const maps::PlaneMap& map, const Eigen::Vector3d& t) {
  std::vector<maps::PlanarPolygon> polygons;
  for (const maps::PlanarPolygon& polygon : map.polygons) {
    if (polygon.kind != maps::SurfaceKind::Wall || t.isZero()) {
      polygons.push_back(polygon);
      continue;
    }
    std::vector<maps::Ring3> holes;
    for (const auto& hole : polygon.holes) holes.push_back(moved(hole, t));
    maps::PlanarPolygon wall;
    EXPECT_TRUE(maps::make_planar_polygon(moved(polygon.outer, t), holes, wall));
    wall.kind = polygon.kind;
    polygons.push_back(wall);
  }
  std::vector<sim::SurfaceMaterial> materials(polygons.size());
  // A cupboard's face 1 m before the sensor: its returns are not the map's and count nothing.
  maps::PlaneMap cupboard;
  cupboard.cells.emplace_back();
  ct::add_box(cupboard, 0, {3.0, 1.0, 0.0}, {3.5, 1.6, 1.8}, false);
  for (const maps::PlanarPolygon& face : cupboard.polygons) {
    polygons.push_back(face);
    materials.push_back({50.0, sim::SurfaceOrigin::Furniture});
  }
  return sim::World(std::move(polygons), std::move(materials), {});
}

std::vector<conicloc::io::StampedPose> one_pose(double x, double y, double yaw) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(x, y, 0.8);
  T.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(0.02, Eigen::Vector3d::UnitX()))
                   .matrix();
  return {{12.5, T}};
}

}  // namespace

TEST(MapFit, WhereTheWorldIsTheMapTheFitIsTheTruth) {
  const maps::PlaneMap room = ct::make_box_room();
  const auto truth = one_pose(2.0, 2.5, 0.4);
  const auto fitted = sim::map_fit_poses(
      room, world_with_walls_moved(room, Eigen::Vector3d::Zero()), ct::vlp16(), truth);
  ASSERT_EQ(fitted.size(), 1u);
  EXPECT_EQ(fitted[0].time_s, 12.5);
  EXPECT_TRUE(fitted[0].pose.isApprox(truth[0].pose, 1e-12));
}

TEST(MapFit, WallsStandingOffTogetherMoveThePoseBack) {
  const maps::PlaneMap room = ct::make_box_room();
  const Eigen::Vector3d t(0.04, -0.03, 0.0);
  const auto truth = one_pose(2.0, 2.5, 0.4);
  const auto fitted = sim::map_fit_poses(room, world_with_walls_moved(room, t), ct::vlp16(), truth);
  ASSERT_EQ(fitted.size(), 1u);
  // Seen from the truth, every wall is t nearer along −n than the map has it: the map explains
  // the returns exactly from the truth moved by −t (floors and ceilings fix z, roll and pitch).
  EXPECT_LT((fitted[0].pose.translation() - (truth[0].pose.translation() - t)).norm(), 1e-6);
  EXPECT_TRUE(fitted[0].pose.linear().isApprox(truth[0].pose.linear(), 1e-6));
}

TEST(MapFit, ADirectionTheReturnsDoNotFixKeepsTheTruth) {
  // A 30 m corridor seen to 6 m: its end walls are out of reach and nothing fixes x.
  const maps::PlaneMap corridor = ct::make_empty_room("corridor", {30.0, 2.5, 3.0});
  const Eigen::Vector3d t(0.05, 0.02, 0.0);
  const auto truth = one_pose(15.0, 1.0, 0.0);
  sim::MapFitConfig config;
  config.max_range_m = 6.0;
  const auto fitted =
      sim::map_fit_poses(corridor, world_with_walls_moved(corridor, t), ct::vlp16(), truth, config);
  ASSERT_EQ(fitted.size(), 1u);
  const Eigen::Vector3d p = fitted[0].pose.translation();
  EXPECT_NEAR(p.x(), 15.0, 1e-6);
  EXPECT_NEAR(p.y(), 1.0 - 0.02, 1e-6);
  EXPECT_NEAR(p.z(), 0.8, 1e-6);
  // With the end walls in reach, x follows them.
  const auto seen_whole =
      sim::map_fit_poses(corridor, world_with_walls_moved(corridor, t), ct::vlp16(), truth);
  EXPECT_NEAR(seen_whole[0].pose.translation().x(), 15.0 - 0.05, 1e-6);
}
