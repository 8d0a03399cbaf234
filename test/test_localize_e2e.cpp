// End to end: `conicloc simulate` a short capture of the shipped example building, then
// `conicloc localize` on it, and compare with the simulator's ground truth.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "eval/trajectory_metrics.hpp"
#include "io/tum_trajectory.hpp"
#include "localizer/conic/pose.hpp"
#include "localizer/filter/relative_motion.hpp"
#include "test/cli_run.hpp"

namespace cl = conicloc::localizer;
namespace fs = std::filesystem;
using conicloc::test::slurp;

namespace {

int run(const std::string& arguments) {
  return conicloc::test::run_conicloc(arguments, "/dev/null");
}

class LocalizeEndToEnd : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("conicloc_e2e_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    simulated_ =
        run("simulate --duration 3 --seed 4 --out " + (dir_ / "run.pcap").string() + " --truth " +
            (dir_ / "truth.tum").string() + " --odom " + (dir_ / "odom.tum").string()) == 0;
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  static inline fs::path dir_;
  static inline bool simulated_ = false;
};

}  // namespace

TEST_F(LocalizeEndToEnd, TracksWithOdometryWithin5cmAndHalfADegreeAndRepeatsExactly) {
  ASSERT_TRUE(simulated_);
  const auto truth = conicloc::io::read_tum((dir_ / "truth.tum").string());
  ASSERT_GT(truth.size(), 20u);
  const std::string init = conicloc::test::init_argument(truth.front().pose);
  std::string common =
      "localize --pcap " + (dir_ / "run.pcap").string() + " --odom " +
      (dir_ / "odom.tum").string() + " --init " + init +
      " --init-sigma 0.05,0.05,1 --seed 3 --init-particles 300 --min-particles 200";
  ASSERT_EQ(run(common + " --threads 2 --out " + (dir_ / "a.tum").string()), 0);
  ASSERT_EQ(run(common + " --threads 1 --out " + (dir_ / "b.tum").string()), 0);
  EXPECT_EQ(slurp(dir_ / "a.tum"), slurp(dir_ / "b.tum"));  // same seed: same bytes

  const auto estimate = conicloc::io::read_tum((dir_ / "a.tum").string());
  ASSERT_GE(estimate.size(), truth.size() - 2);
  double sum_xy = 0.0, sum_yaw = 0.0;
  std::size_t n = 0;
  for (std::size_t k = 5; k < estimate.size(); ++k) {
    if (estimate[k].time_s > truth.back().time_s) break;
    const cl::Pose3 t = *conicloc::eval::interpolate_pose(truth, estimate[k].time_s, 0.1);
    sum_xy += (estimate[k].pose.translation() - t.translation()).head<2>().squaredNorm();
    const double yaw = cl::angle_difference(cl::yaw_of(estimate[k].pose), cl::yaw_of(t));
    sum_yaw += yaw * yaw;
    ++n;
  }
  ASSERT_GT(n, 15u);
  EXPECT_LT(std::sqrt(sum_xy / n), 0.05);                 // RMS position error
  EXPECT_LT(std::sqrt(sum_yaw / n) * 180.0 / M_PI, 0.5);  // RMS heading error
}
