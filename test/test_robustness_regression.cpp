// The robustness issue's bounds, end to end through the binary, tracked from the first pose
// without odometry: a robot in a small generated corridor building, and a hand-held sensor in a
// public model of long corridors (PNU, where it is present). The full corpus (every building,
// scenario and seed) is `conicloc evaluate --sweep robustness`. conic-segment does not meet these
// bounds in the generated corridor yet (about 11 cm xy RMSE: it lags along the corridor in the
// first seconds, before the scans have shown its speed); it joins that test when it does.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "eval/trajectory_metrics.hpp"
#include "io/tum_trajectory.hpp"
#include "localizer/conic/pose.hpp"
#include "test/cli_run.hpp"
#include "test/shared_buildings.hpp"

namespace cl = conicloc::localizer;
namespace fs = std::filesystem;

namespace {

class CorridorWithoutOdometry : public ::testing::TestWithParam<std::string> {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("conicloc_robust_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    const std::string map = (dir_ / "corridor.gml").string();
    ready_ = run("generate-building --kind corridor --seed 1 --out " + map) == 0 &&
             run("simulate --map " + map + " --duration 8 --seed 1 --out " +
                 (dir_ / "run.pcap").string() + " --truth " + (dir_ / "truth.tum").string()) == 0;
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static int run(const std::string& arguments) {
    return conicloc::test::run_conicloc(arguments, dir_ / "log.txt");
  }

  static inline fs::path dir_;
  static inline bool ready_ = false;
};

// Never lost (max xy error ≤ 0.5 m), xy RMSE ≤ 5 cm, heading RMSE ≤ 0.5°, no recovery: the
// estimate `estimate` and its details `details` against `truth`.
void expect_within_bounds(const std::vector<conicloc::io::StampedPose>& truth,
                          const fs::path& estimate, const fs::path& details,
                          std::size_t min_poses) {
  const auto poses = conicloc::io::read_tum(estimate.string());
  double sum_xy = 0.0, sum_yaw = 0.0, max_xy = 0.0;
  std::size_t n = 0;
  for (const auto& pose : poses) {
    const auto t = conicloc::eval::interpolate_pose(truth, pose.time_s, 0.1);
    if (!t) continue;
    const double xy = (pose.pose.translation() - t->translation()).head<2>().norm();
    const double yaw = cl::angle_difference(cl::yaw_of(pose.pose), cl::yaw_of(*t));
    sum_xy += xy * xy, sum_yaw += yaw * yaw, max_xy = std::max(max_xy, xy);
    ++n;
  }
  ASSERT_GT(n, min_poses);
  EXPECT_LE(max_xy, 0.5);                                 // never lost
  EXPECT_LE(std::sqrt(sum_xy / n), 0.05);                 // xy RMSE
  EXPECT_LE(std::sqrt(sum_yaw / n) * 180.0 / M_PI, 0.5);  // heading RMSE
  for (const double recovered : conicloc::test::csv_column(details, "recovered"))
    EXPECT_EQ(recovered, 0.0);
}

}  // namespace

TEST_P(CorridorWithoutOdometry, NeverLostWithin5cmAndHalfADegree) {
  ASSERT_TRUE(ready_) << conicloc::test::slurp(dir_ / "log.txt");
  const auto truth = conicloc::io::read_tum((dir_ / "truth.tum").string());
  const fs::path estimate = dir_ / (GetParam() + ".tum");
  const fs::path details = dir_ / (GetParam() + ".csv");
  ASSERT_EQ(run("localize --map " + (dir_ / "corridor.gml").string() + " --pcap " +
                (dir_ / "run.pcap").string() + " --init " +
                conicloc::test::init_argument(truth.front().pose) + " --model " + GetParam() +
                " --out " + estimate.string() + " --details " + details.string()),
            0);
  expect_within_bounds(truth, estimate, details, 70);
}

INSTANTIATE_TEST_SUITE_P(ConicModels, CorridorWithoutOdometry, ::testing::Values("conic-beam"),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                           std::string name = param.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

// A hand-held sensor (1.4 m, walking sway of ±2–3°) in PNU's long corridors, 6 s: with the sensor's
// tilt taken as level, the inlier fraction of the true pose fell under the lost test's 20 % within
// 0.6 s (the far returns miss by range × tilt), and conic-segment was lost (40 m RMSE, 5
// recoveries; conic-beam 0.86 m, 2); with the tilt measured from each scan
// (localizer/scan_tilt.hpp) both track it within 4 cm.
class HandheldInLongCorridors : public ::testing::TestWithParam<std::string> {
 protected:
  static void SetUpTestSuite() {
    map_ = conicloc::test::shared_indoorgml_dir() / "PNU-bldg313-4F-2D-190612.gml";
    if (!fs::exists(map_)) return;
    dir_ = fs::temp_directory_path() / ("conicloc_handheld_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    ready_ =
        run("simulate --map " + map_.string() + " --duration 6 --seed 1 --motion handheld --out " +
            (dir_ / "run.pcap").string() + " --truth " + (dir_ / "truth.tum").string()) == 0;
  }
  static void TearDownTestSuite() {
    if (!dir_.empty()) fs::remove_all(dir_);
  }
  static int run(const std::string& arguments) {
    return conicloc::test::run_conicloc(arguments, dir_ / "log.txt");
  }

  static inline fs::path map_;
  static inline fs::path dir_;
  static inline bool ready_ = false;
};

TEST_P(HandheldInLongCorridors, NeverLostWithin5cmAndHalfADegree) {
  if (!fs::exists(map_)) GTEST_SKIP() << map_ << " is absent (../shared/data)";
  ASSERT_TRUE(ready_) << conicloc::test::slurp(dir_ / "log.txt");
  const auto truth = conicloc::io::read_tum((dir_ / "truth.tum").string());
  const fs::path estimate = dir_ / (GetParam() + ".tum");
  const fs::path details = dir_ / (GetParam() + ".csv");
  ASSERT_EQ(run("localize --map " + map_.string() + " --pcap " + (dir_ / "run.pcap").string() +
                " --init " + conicloc::test::init_argument(truth.front().pose) + " --model " +
                GetParam() + " --out " + estimate.string() + " --details " + details.string()),
            0);
  expect_within_bounds(truth, estimate, details, 50);
}

INSTANTIATE_TEST_SUITE_P(ConicModels, HandheldInLongCorridors,
                         ::testing::Values("conic-beam", "conic-segment"),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                           std::string name = param.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });
