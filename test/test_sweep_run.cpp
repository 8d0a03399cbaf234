// One run of an evaluation sweep through the run library (run/sweep_run.hpp): the scenario's
// filter start, the simulated recording's files, and a localizer setting run over it.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <vector>

#include "eval/sweep_scenario.hpp"
#include "eval/trajectory_metrics.hpp"
#include "io/indoorgml.hpp"
#include "io/tum_trajectory.hpp"
#include "run/sweep_run.hpp"
#include "test/temp_path.hpp"

namespace cl = conicloc::localizer;
namespace cr = conicloc::run;
namespace fs = std::filesystem;

namespace {

class SweepRun : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(CONICLOC_EXAMPLE_MAP)) GTEST_SKIP() << "no example building";
    map_ = conicloc::io::load_indoorgml(CONICLOC_EXAMPLE_MAP).map;
    dir_ = conicloc::test::unique_temp_path("sweep_run");
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  conicloc::maps::PlaneMap map_;
  fs::path dir_;
};

}  // namespace

TEST(SearchPhase, HoldsTheScansOfASearchUpToTheOneThatConverged) {
  using Status = cl::LocalizerStatus;
  const auto phases = [](bool global_start, const std::vector<Status>& statuses) {
    cr::SearchPhase phase(global_start);
    std::vector<bool> searched;
    for (const Status status : statuses) searched.push_back(phase.add(status));
    return searched;
  };
  // A global start whose first scan converged: that scan is the search's.
  EXPECT_EQ(phases(true, {Status::Tracking, Status::Tracking}), (std::vector<bool>{true, false}));
  EXPECT_EQ(
      phases(true, {Status::Uncertain, Status::Uncertain, Status::Tracking, Status::Tracking}),
      (std::vector<bool>{true, true, true, false}));
  // Tracking from a given pose, then lost: the lost scan and the recovery up to the scan that
  // converged again.
  EXPECT_EQ(phases(false, {Status::Tracking, Status::Lost, Status::Relocalizing, Status::Tracking,
                           Status::Tracking}),
            (std::vector<bool>{false, true, true, true, false}));
  // An unsure scan while tracking: it and the scan that is sure again.
  EXPECT_EQ(
      phases(false, {Status::Tracking, Status::Uncertain, Status::Tracking, Status::Tracking}),
      (std::vector<bool>{false, true, true, false}));
}

TEST_F(SweepRun, FilterStartsOfTheScenarios) {
  const cl::Pose3 truth = cl::make_pose(2.0, 3.0, 0.8, 0.3) * cl::make_pose(0, 0, 0, 0, 0.01, 0.0);
  const auto tracking =
      cr::sweep_filter_start(map_, conicloc::eval::FilterStartMode::Tracking, truth);
  EXPECT_FALSE(tracking.global);
  // Around the true position and yaw, level: the sigma of eval::FilterStartMode::Tracking.
  EXPECT_TRUE(tracking.pose.isApprox(cl::make_pose(2.0, 3.0, 0.8, cl::yaw_of(truth))));
  EXPECT_DOUBLE_EQ(tracking.sigma[0], 0.2);
  EXPECT_DOUBLE_EQ(tracking.sigma[5], 5.0 * M_PI / 180.0);

  const auto kidnap = cr::sweep_filter_start(map_, conicloc::eval::FilterStartMode::Kidnap, truth);
  EXPECT_FALSE(kidnap.global);
  const Eigen::Vector3d off = kidnap.pose.translation() - truth.translation();
  EXPECT_NEAR(off.head<2>().norm(), 3.0, 1e-12);
  EXPECT_NEAR(cl::angle_difference(cl::yaw_of(kidnap.pose), cl::yaw_of(truth)), M_PI / 2, 1e-12);
  EXPECT_DOUBLE_EQ(kidnap.sigma[0], 0.1);
  EXPECT_DOUBLE_EQ(kidnap.sigma[5], 2.0 * M_PI / 180.0);

  EXPECT_TRUE(cr::sweep_filter_start(map_, conicloc::eval::FilterStartMode::Global, truth).global);
}

TEST_F(SweepRun, SettingRunOverARecordingRepeatsExactly) {
  const conicloc::eval::Scenario& robot = *conicloc::eval::find_scenario("robot");
  const auto recording = cr::simulate_recording(map_, "example", robot, 3, 3.0, dir_);
  EXPECT_EQ(recording.name, "example-robot-s3");
  for (const char* suffix : {".pcap", ".truth.tum", ".odom.tum"}) {
    EXPECT_TRUE(fs::exists(dir_ / (recording.name + suffix))) << suffix;
  }
  EXPECT_EQ(conicloc::io::read_tum((dir_ / "example-robot-s3.truth.tum").string()).size(),
            recording.truth.size());
  EXPECT_DOUBLE_EQ(recording.sensor_height_m, 0.8);  // a robot's mount

  const conicloc::eval::LocalizerSetting setting{"conic-beam", 200, 300};
  const auto first = cr::localize_recording(map_, false, robot, 3, recording, setting, 1);
  const auto again = cr::localize_recording(map_, false, robot, 3, recording, setting, 2);
  ASSERT_GT(first.estimate.size(), 10u);
  EXPECT_EQ(first.estimate.size(), first.summary.scans);
  EXPECT_GT(first.mean_particles, 0.0);
  EXPECT_LE(first.mean_particles, 200.0);  // the setting's maximum
  ASSERT_EQ(again.estimate.size(), first.estimate.size());
  for (std::size_t k = 0; k < first.estimate.size(); ++k) {
    EXPECT_EQ(again.estimate[k].time_s, first.estimate[k].time_s) << k;
    EXPECT_EQ(again.estimate[k].pose.matrix(), first.estimate[k].pose.matrix()) << k;
  }
  // Tracked from near the first true pose with odometry: within a decimetre once settled.
  std::size_t scored = 0;
  for (std::size_t k = 5; k < first.estimate.size(); ++k) {
    const auto truth =
        conicloc::eval::interpolate_pose(recording.truth, first.estimate[k].time_s, 0.15);
    if (!truth) continue;
    EXPECT_LT((truth->translation() - first.estimate[k].pose.translation()).norm(), 0.1) << k;
    ++scored;
  }
  EXPECT_GT(scored, 10u);
}
