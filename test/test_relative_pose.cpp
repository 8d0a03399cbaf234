// calib/relative_pose: a second sensor's pose on the carrier recovered exactly from noise-free
// returns of known planes; the first sensor's mounting error carried into its covariance; a
// corridor's unmeasured direction flagged; and the association near an edge chosen by the ray,
// not by the range noise.
#include <gtest/gtest.h>

#include <cmath>

#include "calib/plane_association.hpp"
#include "calib/relative_pose.hpp"
#include "localizer/conic/pose.hpp"
#include "sensor/builtin_calibration.hpp"
#include "synthetic_room.hpp"

namespace conicloc::calib {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kExact = 1e-9;  // metres and radians: noise-free data fit to rounding

// The first sensor's calibration as known exactly: a tilted mounting and a few scan poses.
CalibrationResult first_sensor(const std::vector<ScanPose>& poses) {
  CalibrationResult first;
  first.mounting = {1.1, 1.5 * kDeg, -2.0 * kDeg};
  first.poses = poses;
  for (ScanPose& pose : first.poses) {  // 0.8 m/s forward, 0.2 m/s left, 15°/s
    pose.vx_mps = 0.8;
    pose.vy_mps = 0.2;
    pose.yaw_rate_rps = 15.0 * kDeg;
  }
  return first;
}

// Every laser of the second sensor fired every 2° from every scan while the carrier moves 8 cm
// forward, 2 cm left and turns 1.5° over the turn (0.1 s): at T_map_first(τ) · T_fs, the first
// sensor's pose at the firing (calibration_model.hpp).
std::vector<Return> fire_second(const maps::PlaneMap& map, const CalibrationResult& first,
                                const Eigen::Isometry3d& T_fs,
                                const sensor::LaserCalibration& calibration, bool moving = true) {
  std::vector<Return> returns;
  for (int s = 0; s < static_cast<int>(first.poses.size()); ++s) {
    for (int k = 0; k < calibration.ring_count(); ++k) {
      const sensor::Laser& laser = calibration.lasers[k];
      for (int step = 0; step < 180; ++step) {
        const double tau = moving ? 0.1 * (step / 180.0 - 1.0) : 0.0;  // reference: the end
        const Eigen::Isometry3d T = map_from_fire(first.mounting, first.poses[s], tau) * T_fs;
        const double theta = step * 2.0 * kDeg + 0.21;
        const Eigen::Vector3d direction(std::cos(laser.elevation_rad) * std::cos(theta),
                                        std::cos(laser.elevation_rad) * std::sin(theta),
                                        std::sin(laser.elevation_rad));
        const double range = test::cast_ray(
            map, T * Eigen::Vector3d(0, 0, laser.vertical_offset_m), T.linear() * direction);
        if (!std::isfinite(range) || range < 0.5) continue;
        Return r;
        r.laser = k;
        r.scan = s;
        r.azimuth_rad = theta;
        r.range_m = range;
        r.time_s = tau;
        returns.push_back(r);
      }
    }
  }
  return returns;
}

// Where the second sensor really is, and a start a few cm and degrees off it.
const Eigen::Isometry3d kTruth = localizer::make_pose(0.12, -0.25, 0.35, 88.0 * kDeg, -4.0 * kDeg,
                                                      3.0 * kDeg);
const Eigen::Isometry3d kStart = localizer::make_pose(0.15, -0.22, 0.33, 90.0 * kDeg,
                                                      -3.0 * kDeg, 2.0 * kDeg);

CalibrationConfig exact_map() {
  CalibrationConfig config;
  config.map_sigma_m = 0.0;
  return config;
}

TEST(RelativePose, RecoversTheSecondSensorExactlyInABoxRoom) {
  const maps::PlaneMap map = test::make_box_room();
  const auto calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  const CalibrationResult first =
      first_sensor({{2.5, 2.0, 0.3, 0.0}, {5.0, 3.5, 1.9, 0.0}, {8.5, 4.0, 2.8, 0.0}});
  const auto returns = fire_second(map, first, kTruth, calibration);
  const RelativePoseEstimate estimate =
      fit_relative_pose(map, first, calibration, returns, kStart, exact_map());
  EXPECT_TRUE(estimate.converged);
  EXPECT_TRUE(estimate.all_observable()) << estimate.missing;
  EXPECT_LT((estimate.T_first_second.translation() - kTruth.translation()).norm(), kExact);
  EXPECT_LT(Eigen::AngleAxisd(estimate.T_first_second.linear().transpose() * kTruth.linear()).angle(),
            kExact);
  EXPECT_LT(estimate.rms_m, kExact);
  EXPECT_GT(estimate.returns, returns.size() / 2);
  EXPECT_EQ(estimate.planes, 9);  // the room's six faces and the pillar's sides facing the scans
  for (int i = 0; i < kRelativePoseParameters; ++i) {
    EXPECT_LT(std::sqrt(estimate.covariance(i, i)), 1e-6) << "parameter " << i;
  }
}

TEST(RelativePose, TheFirstCalibrationsPlaneCorrectionsAreUsed) {
  // The room's wall at x = 0 really stands 3 cm further in, as the first calibration found
  // (its plane correction): the second sensor's rays meet it there.
  const maps::PlaneMap map = test::make_box_room();
  maps::PlaneMap world = map;
  ASSERT_TRUE(maps::make_planar_polygon(
      {{0.03, 0, 0}, {0.03, 6, 0}, {0.03, 6, 3}, {0.03, 0, 3}}, {}, world.polygons[2]));
  ASSERT_NEAR(world.polygons[2].plane.normal.x(), 1.0, 1e-12);  // faces the room, as before
  const auto calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  CalibrationResult first =
      first_sensor({{2.5, 2.0, 0.3, 0.0}, {5.0, 3.5, 1.9, 0.0}, {8.5, 4.0, 2.8, 0.0}});
  const auto returns = fire_second(world, first, kTruth, calibration);
  PlaneEstimate wall;
  wall.polygon = 2;
  wall.correction.offset_m = 0.03;  // along the normal, into the room
  first.planes = {wall};
  const RelativePoseEstimate estimate =
      fit_relative_pose(map, first, calibration, returns, kStart, exact_map());
  EXPECT_LT((estimate.T_first_second.translation() - kTruth.translation()).norm(), kExact);
  EXPECT_LT(estimate.rms_m, kExact);
  first.planes.clear();  // without it, the wall's returns are 3 cm off
  EXPECT_GT(fit_relative_pose(map, first, calibration, returns, kStart, exact_map()).rms_m, 1e-3);
}

TEST(RelativePose, AStartDecimetresOffInHeightIsFoundByTheVote) {
  // Localized on its own, the second sensor's height is the filter's assumption: 30 cm off.
  const maps::PlaneMap map = test::make_box_room();
  const auto calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  const CalibrationResult first =
      first_sensor({{2.5, 2.0, 0.3, 0.0}, {5.0, 3.5, 1.9, 0.0}, {8.5, 4.0, 2.8, 0.0}});
  const auto returns = fire_second(map, first, kTruth, calibration);
  Eigen::Isometry3d start = kStart;
  start.translation().z() -= 0.30;
  const RelativePoseEstimate estimate =
      fit_relative_pose(map, first, calibration, returns, start, exact_map(), 1.0);
  EXPECT_LT((estimate.T_first_second.translation() - kTruth.translation()).norm(), kExact);
  EXPECT_LT(estimate.rms_m, kExact);
}

TEST(RelativePose, TheFirstSensorsHeightErrorReachesTheSecondSensorsHeight) {
  // Held as known, a first mounting 1 cm off in height would move the second sensor by 1 cm
  // along the carrier's vertical: its z std. dev. is the height's σ (the first frame is tilted
  // by 2.5°, so z takes cos of it), whatever the returns' own noise.
  const maps::PlaneMap map = test::make_box_room();
  const auto calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  CalibrationResult first =
      first_sensor({{2.5, 2.0, 0.3, 0.0}, {5.0, 3.5, 1.9, 0.0}, {8.5, 4.0, 2.8, 0.0}});
  const auto returns = fire_second(map, first, kTruth, calibration);
  first.mounting_sigma = {0.01, 0.0, 0.0};
  const RelativePoseEstimate estimate =
      fit_relative_pose(map, first, calibration, returns, kStart, exact_map());
  const double tilt = std::acos(std::cos(first.mounting.roll_rad) * std::cos(first.mounting.pitch_rad));
  EXPECT_NEAR(std::sqrt(estimate.covariance(2, 2)), 0.01 * std::cos(tilt), 1e-5);
  EXPECT_LT(std::sqrt(estimate.covariance(0, 0)), 0.001);  // x and y barely move with the height
  EXPECT_LT(std::sqrt(estimate.covariance(5, 5)), 1e-5);   // nor does the yaw
}

TEST(RelativePose, SigmasCountResidualsBeyondHubersKAsCarryingNoCurvature) {
  // Each return twice, ±0.5·k along the ray, and again ±1.5·k: the twins cancel at the truth,
  // and those beyond Huber's k pull only with ψ = ±k and hold nothing (ψ' = 0). Huber's
  // covariance (Σψ²/dof)/ρ·(Σψ'·JJᵀ)⁻¹ is then per ray (2·0.5² + 2)·k²/2 · (2·JJᵀ)⁻¹ against
  // 2·0.5²·k²/2 · (2·JJᵀ)⁻¹ with the inner twins alone: every σ √5 times theirs. The fit's
  // weights k/|e| in place of ψ' (and Σψ·e for Σψ²) give 1.45 times (calibration's same test).
  maps::PlaneMap map = test::make_box_room();
  map.polygons.resize(6);  // without the pillar, whose foot the twins could straddle
  map.cells[0].polygons.resize(6);
  const auto calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  const CalibrationResult first =
      first_sensor({{2.5, 2.0, 0.3, 0.0}, {5.0, 3.5, 1.9, 0.0}, {8.5, 4.0, 2.8, 0.0}});
  const CalibrationConfig config = exact_map();
  std::vector<Return> inner, both;
  for (const Return& ret : fire_second(map, first, kTruth, calibration)) {
    for (const double a : {-0.5, 0.5, -1.5, 1.5}) {
      Return twin = ret;
      twin.range_m += a * config.huber_m;
      both.push_back(twin);
      if (std::abs(a) < 1.0) inner.push_back(twin);
    }
  }
  const RelativePoseEstimate near =
      fit_relative_pose(map, first, calibration, inner, kStart, config);
  const RelativePoseEstimate wide =
      fit_relative_pose(map, first, calibration, both, kStart, config);
  ASSERT_TRUE(near.all_observable() && wide.all_observable()) << near.missing << wide.missing;
  EXPECT_LT((wide.T_first_second.translation() - kTruth.translation()).norm(), 1e-7);
  const double expected = std::sqrt(5.0);
  for (int i = 0; i < kRelativePoseParameters; ++i) {
    ASSERT_GT(near.covariance(i, i), 0.0) << i;
    EXPECT_NEAR(std::sqrt(wide.covariance(i, i) / near.covariance(i, i)), expected, 0.01 * expected)
        << "parameter " << i;
  }
}

TEST(RelativePose, ACorridorWithoutEndsLeavesTheTranslationAlongItUnmeasured) {
  // Floor, ceiling and two side walls, 60 m long: every plane is parallel to x.
  maps::PlaneMap map;
  map.storeys.push_back({"ground", 0.0, 3.0});
  maps::Cell cell;
  cell.storey = 0;
  map.cells.push_back(cell);
  const double lo = -30.0, hi = 30.0;
  test::add_quad(map, 0, {lo, 0, 0}, {hi, 0, 0}, {hi, 3, 0}, {lo, 3, 0});  // floor
  test::add_quad(map, 0, {lo, 0, 3}, {lo, 3, 3}, {hi, 3, 3}, {hi, 0, 3});  // ceiling
  test::add_quad(map, 0, {lo, 0, 0}, {lo, 0, 3}, {hi, 0, 3}, {hi, 0, 0});  // y = 0
  test::add_quad(map, 0, {lo, 3, 0}, {hi, 3, 0}, {hi, 3, 3}, {lo, 3, 3});  // y = 3
  const auto calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  // The carrier drives along the corridor (yaw 0): the first sensor's x is the corridor's.
  CalibrationResult first = first_sensor({{-4.0, 1.5, 0.0, 0.0}, {0.0, 1.4, 0.0, 0.0}});
  first.mounting = {1.1, 0.0, 0.0};
  const Eigen::Isometry3d truth = localizer::make_pose(0.12, -0.25, 0.35, 30.0 * kDeg);
  // Standing still: a carrier turning within the scan would carry x across the side walls.
  const auto returns = fire_second(map, first, truth, calibration, false);
  const RelativePoseEstimate estimate = fit_relative_pose(
      map, first, calibration, returns, localizer::make_pose(0.12, -0.22, 0.33, 31.0 * kDeg),
      exact_map());
  EXPECT_FALSE(estimate.observable[0]) << "x is along the corridor";
  for (int i = 1; i < kRelativePoseParameters; ++i) {
    EXPECT_TRUE(estimate.observable[i]) << "parameter " << i << ": " << estimate.missing;
  }
  EXPECT_FALSE(estimate.all_observable());
  EXPECT_NE(estimate.missing.find("x"), std::string::npos) << estimate.missing;
  EXPECT_TRUE(std::isnan(estimate.covariance(0, 0)));  // no variance for what is not measured
  // What is measured is still right.
  EXPECT_NEAR(estimate.T_first_second.translation().y(), -0.25, 1e-6);
  EXPECT_NEAR(estimate.T_first_second.translation().z(), 0.35, 1e-6);
}

TEST(RelativePose, BadInputsAreErrors) {
  const maps::PlaneMap map = test::make_box_room();
  const auto calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  const CalibrationResult first = first_sensor({{2.5, 2.0, 0.3, 0.0}});
  Return bad;
  bad.scan = 1;  // only scan 0 exists
  bad.range_m = 2.0;
  EXPECT_THROW(fit_relative_pose(map, first, calibration, {bad}, kStart, exact_map()),
               std::invalid_argument);
  Return far;
  far.range_m = 400.0;  // nowhere near a plane
  EXPECT_THROW(fit_relative_pose(map, first, calibration, {far}, kStart, exact_map()),
               std::invalid_argument);
}

TEST(PlaneAssociation, ReturnsByAnEdgeAreKeptByWhereTheirRayMeetsTheSurface) {
  // Rays from 1 m up hitting the floor 0–30 cm short of a wall's foot (x = 10), each recorded
  // twice, with the range ±3 cm off. The nearest polygon to the noisy point would keep the near
  // twin and move the far one onto the wall or off the floor (the floor seen higher); kept by
  // where the ray meets the floor, twins stay together and the bias is 0.
  const maps::PlaneMap map = test::make_box_room();
  const maps::PlaneIndex index(map);
  const Eigen::Vector3d origin(7.0, 3.0, 1.0);
  const int floor = 0;
  const auto mean_floor_height = [&](const auto& associate, int& kept) {
    double sum = 0.0;
    kept = 0;
    for (int i = 0; i <= 30; ++i) {
      const Eigen::Vector3d hit(10.0 - 0.01 * i, 3.0, 0.0);
      const Eigen::Vector3d direction = (hit - origin).normalized();
      const double range = (hit - origin).norm();
      for (const double noise : {-0.03, 0.03}) {
        const Eigen::Vector3d point = origin + (range + noise) * direction;
        if (associate(point) != floor) continue;
        sum += point.z();
        ++kept;
      }
    }
    return kept > 0 ? sum / kept : 0.0;
  };
  int kept = 0;
  const double by_ray = mean_floor_height(
      [&](const Eigen::Vector3d& p) {
        return associated_polygon(map, index, origin, p, 0.10, 0.10);
      },
      kept);
  EXPECT_EQ(kept % 2, 0);
  EXPECT_GT(kept, 20);
  EXPECT_NEAR(by_ray, 0.0, 1e-12);
  // A floor hit within the margin of its edge is left out, not handed to the wall beside it.
  const Eigen::Vector3d by_the_foot(9.95, 3.0, 0.0);
  EXPECT_EQ(associated_polygon(map, index, origin, by_the_foot, 0.10, 0.10), -1);
  EXPECT_EQ(associated_polygon(map, index, origin, by_the_foot, 0.10, 0.0), floor);
  // A ray parallel to the plane, or pointing away from it, never meets it.
  EXPECT_FALSE(ray_meets_inside(map.polygons[floor], origin, {1, 0, 0}, 0.0));
  EXPECT_FALSE(ray_meets_inside(map.polygons[floor], origin, {0, 0, 1}, 0.0));
  EXPECT_TRUE(ray_meets_inside(map.polygons[floor], origin, {0, 0, -1}, 0.10));
  // Nor from behind: a one-sided floor faces up, and solid lies below it.
  EXPECT_FALSE(ray_meets_inside(map.polygons[floor], {7.0, 3.0, -1.0}, {0, 0, 1}, 0.0));
}

TEST(PlaneAssociation, AReturnMeasuredLongBehindAThinWallStaysOnIt) {
  // The wall x = 0 and, 8 cm behind it, the next room's face (facing away, x = −0.08): rays from
  // inside the room, each recorded twice with the range ±6 cm off. A long twin near normal
  // incidence lies nearer the next room's face, which its ray meets from behind: the nearest
  // polygon dropped it (109 of 306 here), so the wall kept short returns and was seen 2.7 cm
  // nearer. The first polygon the ray meets from its front keeps both twins.
  maps::PlaneMap map = test::make_box_room();
  const int wall = 2;
  ASSERT_NEAR(map.polygons[wall].plane.normal.x(), 1.0, 1e-12);
  test::add_quad(map, 0, {-0.08, 0, 0}, {-0.08, 0, 3}, {-0.08, 6, 3}, {-0.08, 6, 0});
  ASSERT_NEAR(map.polygons.back().plane.normal.x(), -1.0, 1e-12);
  const maps::PlaneIndex index(map);
  const Eigen::Vector3d origin(1.5, 3.0, 1.2);
  int twins = 0, kept = 0;
  double depth = 0.0;  // Σ x of the kept points
  for (double y = 1.0; y <= 5.0; y += 0.25) {
    for (double z = 0.5; z <= 2.5; z += 0.25) {
      const Eigen::Vector3d hit(0.0, y, z);
      const Eigen::Vector3d direction = (hit - origin).normalized();
      for (const double noise : {-0.06, 0.06}) {
        const Eigen::Vector3d point = origin + ((hit - origin).norm() + noise) * direction;
        ++twins;
        if (associated_polygon(map, index, origin, point, 0.10, 0.10) != wall) continue;
        ++kept;
        depth += point.x();
      }
    }
  }
  EXPECT_EQ(kept, twins);
  EXPECT_NEAR(depth / kept, 0.0, 1e-12);
}

TEST(PlaneAssociation, TheRayDecidesAndPassesOtherPolygonsClearOfTheirEdges) {
  // A partition 5 cm in front of the room's wall x = 10, facing the room, its end at y = 3.
  maps::PlaneMap map = test::make_box_room();
  const int wall = 3;
  ASSERT_NEAR(map.polygons[wall].plane.normal.x(), -1.0, 1e-12);
  test::add_quad(map, 0, {9.95, 0, 0}, {9.95, 0, 3}, {9.95, 3, 3}, {9.95, 3, 0});
  const int partition = static_cast<int>(map.polygons.size()) - 1;
  ASSERT_NEAR(map.polygons[partition].plane.normal.x(), -1.0, 1e-12);
  const maps::PlaneIndex index(map);
  const auto at = [&](double y, double x_point, double gate) {
    return associated_polygon(map, index, {5.0, y, 1.2}, {x_point, y, 1.2}, gate, 0.10);
  };
  // On the partition, and measured 5 cm long so that the wall is nearer: the ray meets the
  // partition first, so the return is the partition's.
  EXPECT_EQ(at(2.8, 9.95, 0.10), partition);
  EXPECT_EQ(at(2.8, 10.0, 0.10), partition);
  // Past the partition's end by 5 cm, within the margin: the true ray may be the partition's.
  EXPECT_EQ(at(3.05, 10.0, 0.10), -1);
  // Past it by 30 cm, the partition within the gate yet clear: the wall's.
  EXPECT_EQ(at(3.3, 10.0, 0.5), wall);
}

}  // namespace
}  // namespace conicloc::calib
