// The turn between two scans measured from the scans themselves (localizer/scan_turn.hpp): from
// the rings' range profiles, the previous one seen from where the sensor was expected to go.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "localizer/filter/scan_turn.hpp"
#include "synthetic_room.hpp"

namespace cl = conicloc::localizer;
namespace ct = conicloc::test;

namespace {

// Two scans of `map` from standing poses `a` then `b`; the second rotation fires half a step
// after the first's azimuths, as a real sensor's next rotation does.
std::optional<double> measure(const conicloc::maps::PlaneMap& map, const cl::Pose3& a,
                              const cl::Pose3& b, const Eigen::Vector2d& expected_translation,
                              double azimuth_step_deg = 0.2, double max_range_m = 100.0,
                              int threads = 1) {
  std::mt19937_64 rng(5);
  ct::SyntheticScanOptions options;
  options.azimuth_step_rad = azimuth_step_deg * M_PI / 180.0;
  options.range_sigma_m = 0.005;
  options.max_range_m = max_range_m;
  cl::ScanTurn turn({}, threads);
  EXPECT_FALSE(turn.update(ct::make_scan(map, a, options, rng), expected_translation))
      << "the first scan has nothing to compare with";
  options.azimuth_offset_rad = 0.5 * options.azimuth_step_rad;
  return turn.update(ct::make_scan(map, b, options, rng), expected_translation);
}

// A corridor 40 m × 2.5 m × 3 m with nothing in it, turned by `angle_rad` about its middle
// (20, 1.25), as one cell.
conicloc::maps::PlaneMap corridor(double angle_rad) {
  conicloc::maps::PlaneMap map = ct::make_box_room();
  map.polygons.clear();
  map.cells[0].polygons.clear();
  const Eigen::Vector3d centre(20.0, 1.25, 0.0);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(angle_rad, Eigen::Vector3d::UnitZ()).matrix();
  const auto at = [&](double x, double y, double z) {
    return Eigen::Vector3d(centre + R * (Eigen::Vector3d(x, y, z) - centre));
  };
  const double x0 = 0, x1 = 40, y0 = 0, y1 = 2.5, z1 = 3;
  ct::add_quad(map, 0, at(x0, y0, 0), at(x1, y0, 0), at(x1, y1, 0), at(x0, y1, 0));      // floor
  ct::add_quad(map, 0, at(x0, y0, z1), at(x0, y1, z1), at(x1, y1, z1), at(x1, y0, z1));  // ceiling
  ct::add_quad(map, 0, at(x0, y0, 0), at(x0, y0, z1), at(x1, y0, z1), at(x1, y0, 0));    // y = 0
  ct::add_quad(map, 0, at(x0, y1, 0), at(x1, y1, 0), at(x1, y1, z1), at(x0, y1, z1));    // y = 2.5
  return map;
}

}  // namespace

TEST(ScanTurn, TheTurnOfAMovingSensorIsMeasured) {
  // 8 cm forward and 3 cm left in a's frame, turned by 4°; the translation expected within 2 cm.
  const cl::Pose3 a = cl::make_pose(3.0, 2.5, 1.2, 0.3);
  const cl::Pose3 b = a * cl::make_pose(0.08, 0.03, 0.0, 4.0 * M_PI / 180.0);
  const auto turn = measure(ct::make_box_room(), a, b, Eigen::Vector2d(0.07, 0.015));
  ASSERT_TRUE(turn);
  // Within the std. dev. the filter gives the measurement (the translation expected is 1–2 cm
  // off, which shifts near walls in azimuth).
  EXPECT_NEAR(*turn, 4.0 * M_PI / 180.0, cl::ScanTurnConfig{}.sigma_rad);
}

TEST(ScanTurn, ARoomThatLooksTheSameTurnedIsRefused) {
  // A 36-sided room seen from its centre looks the same turned by 10°: within the ±34° search
  // there are several equal minima, and no turn is claimed.
  conicloc::maps::PlaneMap map = ct::make_box_room();
  map.polygons.clear();
  map.cells[0].polygons.clear();
  const auto corner = [](int k, double z) {
    const double angle = k * M_PI / 18.0;
    return Eigen::Vector3d(3.0 + 3.0 * std::cos(angle), 3.0 + 3.0 * std::sin(angle), z);
  };
  for (int k = 0; k < 36; ++k)  // walls facing the centre
    ct::add_quad(map, 0, corner(k, 0), corner(k, 3), corner(k + 1, 3), corner(k + 1, 0));
  const cl::Pose3 a = cl::make_pose(3.0, 3.0, 1.2, 0.0);
  const cl::Pose3 b = a * cl::make_pose(0.0, 0.0, 0.0, 3.0 * M_PI / 180.0);
  EXPECT_FALSE(measure(map, a, b, Eigen::Vector2d::Zero()));
}

TEST(ScanTurn, ClockwiseTurnsAndSparseRingsToo) {
  // 1200 rpm: a return every 0.4°, coarser than the profile's 0.25° bins.
  const cl::Pose3 a = cl::make_pose(6.0, 4.0, 1.2, -2.0);
  const cl::Pose3 b = a * cl::make_pose(0.0, 0.0, 0.0, -11.0 * M_PI / 180.0);
  const auto turn = measure(ct::make_box_room(), a, b, Eigen::Vector2d::Zero(), 0.4);
  ASSERT_TRUE(turn);
  EXPECT_NEAR(*turn * 180.0 / M_PI, -11.0, 0.1);
}

TEST(ScanTurn, TurnFromTheScansMiddlesToTheirEnds) {
  // Steady turn: the middle-to-middle turn is the end-to-end one.
  const auto steady = cl::ScanTurn::end_to_end(0.05, 0.05, 0.005);
  EXPECT_DOUBLE_EQ(steady.yaw_rad, 0.05);
  EXPECT_DOUBLE_EQ(steady.sigma_rad, 0.005);
  // A turn speeding up: half a scan more of the change, and as much more doubt.
  const auto faster = cl::ScanTurn::end_to_end(0.06, 0.02, 0.005);
  EXPECT_NEAR(faster.yaw_rad, 0.08, 1e-15);
  EXPECT_NEAR(faster.sigma_rad, 0.025, 1e-15);
}

// A corridor whose end walls are beyond the range shows the turn through its walls.
TEST(ScanTurn, AFeaturelessCorridorShowsTheTurn) {
  const auto map = corridor(0.5);
  const cl::Pose3 a = cl::make_pose(20.0, 1.25, 1.2, 0.7);
  const cl::Pose3 b = a * cl::make_pose(0.08, 0.0, 0.0, -2.5 * M_PI / 180.0);
  const auto turn = measure(map, a, b, Eigen::Vector2d(0.08, 0.0), 0.2, 15.0);
  ASSERT_TRUE(turn);
  EXPECT_NEAR(*turn * 180.0 / M_PI, -2.5, 0.15);
}

TEST(ScanTurn, TheSameTurnForAnyThreadCount) {
  // Workers share the rings and the shifts searched; the turn is the same to the last bit.
  const cl::Pose3 a = cl::make_pose(3.0, 2.5, 1.2, 0.3);
  const cl::Pose3 b = a * cl::make_pose(0.08, 0.03, 0.0, -7.0 * M_PI / 180.0);
  const auto one = measure(ct::make_box_room(), a, b, Eigen::Vector2d(0.07, 0.015));
  ASSERT_TRUE(one);
  EXPECT_NEAR(*one, -7.0 * M_PI / 180.0, 0.005);
  for (const int threads : {2, 3, 8}) {
    const auto many =
        measure(ct::make_box_room(), a, b, Eigen::Vector2d(0.07, 0.015), 0.2, 100.0, threads);
    ASSERT_TRUE(many) << threads;
    EXPECT_EQ(*many, *one) << threads;
  }
}
