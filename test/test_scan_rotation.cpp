// The motion between two scans measured from the scans themselves (localizer/scan_rotation.hpp):
// the turn from the rings' range profiles, the translation from the near-level rings.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "localizer/scan_rotation.hpp"
#include "synthetic_room.hpp"

namespace cl = conicloc::localizer;
namespace ct = conicloc::test;

namespace {

// Two scans of the box room (with its off-centre pillar) from standing poses `a` then `b`.
cl::ScanRotation::Motion measure(const cl::Pose3& a, const cl::Pose3& b,
                                 const Eigen::Vector2d& expected_translation,
                                 double azimuth_step_deg = 0.2) {
  const auto map = ct::make_box_room();
  std::mt19937_64 rng(5);
  ct::SyntheticScanOptions options;
  options.azimuth_step_rad = azimuth_step_deg * M_PI / 180.0;
  options.range_sigma_m = 0.005;
  cl::ScanRotation rotation;
  EXPECT_FALSE(rotation.update(ct::make_scan(map, a, options, rng), expected_translation).turn_rad)
      << "the first scan has nothing to compare with";
  return rotation.update(ct::make_scan(map, b, options, rng), expected_translation);
}

}  // namespace

TEST(ScanRotation, TurnAndTranslationOfAStandingSensorAreMeasured) {
  const cl::Pose3 a = cl::make_pose(3.0, 2.5, 1.2, 0.3);
  // 8 cm forward and 3 cm left in a's frame, turned by 4°.
  const cl::Pose3 b = a * cl::make_pose(0.08, 0.03, 0.0, 4.0 * M_PI / 180.0);
  // The expected translation is off by 5 cm: the refinement finds the true one.
  const auto motion = measure(a, b, Eigen::Vector2d(0.03, 0.03));
  ASSERT_TRUE(motion.turn_rad);
  EXPECT_NEAR(*motion.turn_rad * 180.0 / M_PI, 4.0, 0.1);
  ASSERT_TRUE(motion.translation_m);
  EXPECT_NEAR(motion.translation_m->x(), 0.08, 0.015);
  EXPECT_NEAR(motion.translation_m->y(), 0.03, 0.015);
}

TEST(ScanRotation, ClockwiseTurnsAndSparseRingsToo) {
  // 1200 rpm: a return every 0.4°, coarser than the profile's 0.25° bins.
  const cl::Pose3 a = cl::make_pose(6.0, 4.0, 1.2, -2.0);
  const cl::Pose3 b = a * cl::make_pose(0.0, 0.0, 0.0, -11.0 * M_PI / 180.0);
  const auto motion = measure(a, b, Eigen::Vector2d::Zero(), 0.4);
  ASSERT_TRUE(motion.turn_rad);
  EXPECT_NEAR(*motion.turn_rad * 180.0 / M_PI, -11.0, 0.1);
}

TEST(ScanRotation, TurnFromTheScansMiddlesToTheirEnds) {
  // Steady turn: the middle-to-middle turn is the end-to-end one.
  const auto steady = cl::ScanRotation::end_to_end(0.05, 0.05, 0.005);
  EXPECT_DOUBLE_EQ(steady.yaw_rad, 0.05);
  EXPECT_DOUBLE_EQ(steady.sigma_rad, 0.005);
  // A turn speeding up: half a scan more of the change, and as much more doubt.
  const auto faster = cl::ScanRotation::end_to_end(0.06, 0.02, 0.005);
  EXPECT_NEAR(faster.yaw_rad, 0.08, 1e-15);
  EXPECT_NEAR(faster.sigma_rad, 0.025, 1e-15);
}

TEST(ScanRotation, AFeaturelessCorridorDoesNotPinTheTranslationAlongIt) {
  // 40 m × 2.5 m, nothing in it, its end walls beyond the range: moving along the axis changes
  // nothing the sensor sees.
  conicloc::maps::PlaneMap map = ct::make_box_room();
  map.polygons.clear();
  map.cells[0].polygons.clear();
  ct::add_box(map, 0, {0, 0, 0}, {40, 2.5, 3}, true);
  std::mt19937_64 rng(5);
  ct::SyntheticScanOptions options;
  options.azimuth_step_rad = 0.2 * M_PI / 180.0;
  options.max_range_m = 15.0;
  const cl::Pose3 a = cl::make_pose(20.0, 1.25, 1.2, 0.0);
  const cl::Pose3 b = a * cl::make_pose(0.08, 0.0, 0.0, 2.0 * M_PI / 180.0);
  cl::ScanRotation rotation;
  rotation.update(ct::make_scan(map, a, options, rng), Eigen::Vector2d::Zero());
  options.azimuth_offset_rad = 0.1 * M_PI / 180.0;  // the next rotation fires between the last's
  const auto motion = rotation.update(ct::make_scan(map, b, options, rng), Eigen::Vector2d::Zero());
  ASSERT_TRUE(motion.turn_rad);  // the walls still show the turn
  EXPECT_NEAR(*motion.turn_rad * 180.0 / M_PI, 2.0, 0.15);
  EXPECT_FALSE(motion.translation_m) << motion.translation_m->x() << " " << motion.translation_m->y();
}
