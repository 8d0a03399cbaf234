// The pose a map gives a scan (sim/map_fit.hpp): the truth where the world is the map; where every
// wall stands off by one motion M (a shift, a turn about a vertical axis), M⁻¹·T (each residual is
// 0 there); along a direction the returns do not fix, and with nothing in sight, the truth.

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

maps::Ring3 moved(const maps::Ring3& ring, const Eigen::Isometry3d& motion) {
  maps::Ring3 out;
  for (const auto& p : ring) out.push_back(motion * p);
  return out;
}

Eigen::Isometry3d shift(const Eigen::Vector3d& t) {
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  motion.translation() = t;
  return motion;
}

// The world of `map` with every wall moved by `motion` (floors and ceilings, level, stay on their
// planes under a motion that keeps z), and a box the map lacks in it.
sim::World world_with_walls_moved(const maps::PlaneMap& map, const Eigen::Isometry3d& motion) {
  std::vector<maps::PlanarPolygon> polygons;
  for (const maps::PlanarPolygon& polygon : map.polygons) {
    if (polygon.kind != maps::SurfaceKind::Wall || motion.isApprox(Eigen::Isometry3d::Identity())) {
      polygons.push_back(polygon);
      continue;
    }
    std::vector<maps::Ring3> holes;
    for (const auto& hole : polygon.holes) holes.push_back(moved(hole, motion));
    maps::PlanarPolygon wall;
    EXPECT_TRUE(maps::make_planar_polygon(moved(polygon.outer, motion), holes, wall));
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
      room, world_with_walls_moved(room, Eigen::Isometry3d::Identity()), ct::vlp16(), truth);
  ASSERT_EQ(fitted.size(), 1u);
  EXPECT_EQ(fitted[0].time_s, 12.5);
  EXPECT_TRUE(fitted[0].pose.isApprox(truth[0].pose, 1e-12));
}

TEST(MapFit, WallsStandingOffTogetherMoveThePoseBack) {
  const maps::PlaneMap room = ct::make_box_room();
  const Eigen::Vector3d t(0.04, -0.03, 0.0);
  const auto truth = one_pose(2.0, 2.5, 0.4);
  const auto fitted =
      sim::map_fit_poses(room, world_with_walls_moved(room, shift(t)), ct::vlp16(), truth);
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
      sim::map_fit_poses(corridor, world_with_walls_moved(corridor, shift(t)), ct::vlp16(), truth, config);
  ASSERT_EQ(fitted.size(), 1u);
  const Eigen::Vector3d p = fitted[0].pose.translation();
  EXPECT_NEAR(p.x(), 15.0, 1e-6);
  EXPECT_NEAR(p.y(), 1.0 - 0.02, 1e-6);
  EXPECT_NEAR(p.z(), 0.8, 1e-6);
  // With the end walls in reach, x follows them.
  const auto seen_whole =
      sim::map_fit_poses(corridor, world_with_walls_moved(corridor, shift(t)), ct::vlp16(), truth);
  EXPECT_NEAR(seen_whole[0].pose.translation().x(), 15.0 - 0.05, 1e-6);
}

TEST(MapFit, WallsTurnedTogetherTurnThePoseBack) {
  // Every wall turned by 1° about a vertical axis through (5, 3) and shifted by (3, −2) cm: the
  // map explains the returns exactly from M⁻¹·T, in rotation as in translation.
  const maps::PlaneMap room = ct::make_box_room();
  Eigen::Isometry3d motion = shift({0.03, -0.02, 0.0});
  motion.translate(Eigen::Vector3d(5.0, 3.0, 0.0));
  motion.rotate(Eigen::AngleAxisd(M_PI / 180.0, Eigen::Vector3d::UnitZ()));
  motion.translate(Eigen::Vector3d(-5.0, -3.0, 0.0));
  const auto truth = one_pose(2.0, 2.5, 0.4);
  const auto fitted =
      sim::map_fit_poses(room, world_with_walls_moved(room, motion), ct::vlp16(), truth);
  ASSERT_EQ(fitted.size(), 1u);
  const Eigen::Isometry3d expected = motion.inverse() * truth[0].pose;
  EXPECT_LT((fitted[0].pose.translation() - expected.translation()).norm(), 1e-9);
  EXPECT_LT(Eigen::AngleAxisd(fitted[0].pose.linear().transpose() * expected.linear()).angle(),
            1e-9);
  // Fitted on two threads, pose by pose: the same.
  sim::MapFitConfig two;
  two.threads = 2;
  const auto three = {truth[0], truth[0], truth[0]};
  const auto threaded = sim::map_fit_poses(room, world_with_walls_moved(room, motion),
                                           ct::vlp16(), std::vector(three), two);
  ASSERT_EQ(threaded.size(), 3u);
  for (const auto& pose : threaded) EXPECT_TRUE(pose.pose.isApprox(fitted[0].pose, 1e-15));
}

TEST(MapFit, NothingInSightKeepsTheTruth) {
  const maps::PlaneMap room = ct::make_box_room();
  const auto truth = one_pose(2.0, 2.5, 0.4);
  sim::MapFitConfig config;
  config.max_range_m = 0.5;  // every surface is farther
  const auto fitted = sim::map_fit_poses(room, world_with_walls_moved(room, shift({0.1, 0, 0})),
                                         ct::vlp16(), truth, config);
  ASSERT_EQ(fitted.size(), 1u);
  EXPECT_TRUE(fitted[0].pose.isApprox(truth[0].pose, 0.0));
}
