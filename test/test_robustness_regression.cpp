// The robustness issue's bounds, end to end through the library (simulate, localize), tracked from
// the first pose without odometry: a robot in a small generated corridor building, and a hand-held
// sensor in a public model of long corridors (PNU, where it is present). The full corpus (every
// building, scenario and seed) is `conicloc evaluate --sweep robustness`. Both conic models are
// held to them: in the corridor the start's speed is unknown and only the first displacements the
// scans select show it (a velocity drawn per particle at the start was fixed by the first
// resampling, before any motion was seen, and conic-segment lagged along the corridor).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>

#include "eval/trajectory_metrics.hpp"
#include "io/indoorgml.hpp"
#include "localizer/conic/pose.hpp"
#include "sim/building_generator.hpp"
#include "test/shared_buildings.hpp"
#include "test/model_test_name.hpp"
#include "test/simulated_run.hpp"

namespace cl = conicloc::localizer;
namespace ct = conicloc::test;
namespace fs = std::filesystem;

namespace {

// Never lost (max xy error ≤ 0.5 m), xy RMSE ≤ 5 cm, heading RMSE ≤ 0.5°, no recovery: the
// localized run `run` against `truth`.
void expect_within_bounds(const std::vector<conicloc::io::StampedPose>& truth,
                          const ct::LocalizedRun& run, std::size_t min_poses) {
  double sum_xy = 0.0, sum_yaw = 0.0, max_xy = 0.0;
  std::size_t n = 0;
  for (const auto& pose : run.estimate) {
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
  for (const bool recovered : run.recovered) EXPECT_FALSE(recovered);
}

// A building and a recording simulated in it, shared by a suite's models.
struct Recording {
  conicloc::io::LoadedMap loaded;
  ct::SimulatedCapture capture;
};

// `map_path` read as `conicloc simulate` and `localize` read it, and `config` simulated in it
// into `dir`; the error's message when either fails.
std::optional<Recording> record(const fs::path& map_path,
                                const conicloc::sim::SimulationConfig& config, const fs::path& dir,
                                std::string& error) {
  try {
    Recording recording{conicloc::io::load_indoorgml(map_path.string()), {}};
    recording.capture = ct::simulate_capture(recording.loaded.map, config, dir / "run.pcap");
    return recording;
  } catch (const std::exception& e) {
    error = e.what();
    return std::nullopt;
  }
}

class CorridorWithoutOdometry : public ::testing::TestWithParam<std::string> {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("conicloc_robust_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    const fs::path map = dir_ / "corridor.gml";
    std::ofstream(map) << conicloc::sim::generate_building_gml("corridor", 1);
    conicloc::sim::SimulationConfig config;
    config.duration_s = 8.0;
    config.seed = 1;
    recording_ = record(map, config, dir_, error_);
  }
  static void TearDownTestSuite() {
    recording_.reset();
    fs::remove_all(dir_);
  }

  static inline fs::path dir_;
  static inline std::optional<Recording> recording_;
  static inline std::string error_;
};

}  // namespace

TEST_P(CorridorWithoutOdometry, NeverLostWithin5cmAndHalfADegree) {
  ASSERT_TRUE(recording_) << error_;
  auto run = ct::localize_defaults(recording_->loaded, recording_->capture);
  run.localizer.observation.model = GetParam();
  expect_within_bounds(recording_->capture.truth, ct::localize(recording_->loaded.map, run), 70);
}

INSTANTIATE_TEST_SUITE_P(ConicModels, CorridorWithoutOdometry,
                         ::testing::Values("conic-beam", "conic-segment"),
                         conicloc::test::model_test_name);

// A hand-held sensor (1.4 m, walking sway of ±2–3°) in PNU's long corridors, 6 s: with the sensor's
// tilt taken as level, the inlier fraction of the true pose fell under the lost test's 20 % within
// 0.6 s (the far returns miss by range × tilt), and conic-segment was lost (40 m RMSE, 5
// recoveries; conic-beam 0.86 m, 2); with the tilt measured from each scan
// (localizer/scan_tilt.hpp) both track it within 4 cm.
class HandheldInLongCorridors : public ::testing::TestWithParam<std::string> {
 protected:
  static void SetUpTestSuite() {
    map_ = ct::shared_indoorgml_dir() / "PNU-bldg313-4F-2D-190612.gml";
    if (!fs::exists(map_)) return;
    dir_ = fs::temp_directory_path() / ("conicloc_handheld_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    conicloc::sim::SimulationConfig config;
    config.duration_s = 6.0;
    config.seed = 1;
    config.trajectory.style = conicloc::sim::MotionStyle::Handheld;
    recording_ = record(map_, config, dir_, error_);
  }
  static void TearDownTestSuite() {
    recording_.reset();
    if (!dir_.empty()) fs::remove_all(dir_);
  }

  static inline fs::path map_;
  static inline fs::path dir_;
  static inline std::optional<Recording> recording_;
  static inline std::string error_;
};

TEST_P(HandheldInLongCorridors, NeverLostWithin5cmAndHalfADegree) {
  if (!fs::exists(map_)) GTEST_SKIP() << map_ << " is absent (../shared/data)";
  ASSERT_TRUE(recording_) << error_;
  auto run = ct::localize_defaults(recording_->loaded, recording_->capture);
  run.localizer.observation.model = GetParam();
  expect_within_bounds(recording_->capture.truth, ct::localize(recording_->loaded.map, run), 50);
}

INSTANTIATE_TEST_SUITE_P(ConicModels, HandheldInLongCorridors,
                         ::testing::Values("conic-beam", "conic-segment"),
                         conicloc::test::model_test_name);
