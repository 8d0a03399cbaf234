// Global localisation and kidnap recovery: adaptive tempering (localizer/adaptive_tempering.hpp),
// the see-through lost test (localizer/see_through_check.hpp), and both on simulated captures of
// the shipped example building through the `conicloc` binary.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <vector>

#include "io/tum_trajectory.hpp"
#include "localizer/conic/pose.hpp"
#include "localizer/filter/adaptive_tempering.hpp"
#include "localizer/filter/localizer.hpp"
#include "localizer/filter/log_weights.hpp"
#include "localizer/models/see_through_check.hpp"
#include "sensor/builtin_calibration.hpp"
#include "synthetic_room.hpp"
#include "test/cli_run.hpp"

namespace cl = conicloc::localizer;
namespace ct = conicloc::test;
namespace fs = std::filesystem;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::vector<double> uniform_log_weights(std::size_t n) {
  return std::vector<double>(n, -std::log(static_cast<double>(n)));
}

}  // namespace

// ---- Adaptive tempering ----

TEST(AdaptiveTempering, ConditionalEssIsTheEssOfTheNewWeightsForUniformPriors) {
  const std::vector<double> ell = {-3.0, -1.0, -2.5, -10.0, -1.2};
  const auto prior = uniform_log_weights(ell.size());
  for (const double tau : {0.0, 0.3, 1.0, 4.0}) {
    std::vector<double> posterior(ell.size());
    for (std::size_t i = 0; i < ell.size(); ++i) posterior[i] = prior[i] + tau * ell[i];
    cl::normalise_log_weights(posterior);
    EXPECT_NEAR(cl::conditional_ess(prior, ell, tau), cl::effective_sample_size(posterior), 1e-9)
        << tau;
  }
  EXPECT_NEAR(cl::conditional_ess(prior, ell, 0.0), 5.0, 1e-12);
}

TEST(AdaptiveTempering, KeepsTheFullExponentWhenLikelihoodsAgree) {
  const std::vector<double> ell(100, -1234.5);
  EXPECT_EQ(cl::adaptive_tempering_exponent(uniform_log_weights(100), ell, 0.1, 0.5), 0.1);
}

TEST(AdaptiveTempering, LowersTheExponentToTheTargetEssOfAPeakedLikelihood) {
  // Log-likelihoods 10⁴ nats apart, as a scan of thousands of beams gives a spread cloud: the
  // full exponent leaves one particle; the adapted one keeps half of them effective.
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal(0.0, 3000.0);
  std::vector<double> ell(2000);
  for (double& l : ell) l = normal(rng);
  const auto prior = uniform_log_weights(ell.size());
  EXPECT_LT(cl::conditional_ess(prior, ell, 0.1), 2.0);
  const double tau = cl::adaptive_tempering_exponent(prior, ell, 0.1, 0.5);
  EXPECT_LT(tau, 0.1);
  EXPECT_GT(tau, 0.0);
  const double cess = cl::conditional_ess(prior, ell, tau);
  EXPECT_GE(cess, 0.5 * 2000.0);
  // The largest such exponent: a step of the bisection's precision further falls below it.
  EXPECT_LT(cl::conditional_ess(prior, ell, tau + 2e-3 * 0.1), 0.5 * 2000.0);
  // Disabled: the full exponent.
  EXPECT_EQ(cl::adaptive_tempering_exponent(prior, ell, 0.1, 0.0), 0.1);
}

TEST(AdaptiveTempering, MinusInfinityAndNonUniformPriors) {
  // −∞ likelihoods carry no weight at any exponent; the target is relative to the finite mass.
  const std::vector<double> ell = {-kInf, -5.0, -6.0, -kInf, -5.5, -400.0};
  const auto prior = uniform_log_weights(ell.size());
  EXPECT_NEAR(cl::conditional_ess(prior, ell, 0.0), 4.0, 1e-12);
  const double tau = cl::adaptive_tempering_exponent(prior, ell, 1.0, 0.5);
  EXPECT_GE(cl::conditional_ess(prior, ell, tau), 2.0 - 1e-9);
  EXPECT_EQ(cl::conditional_ess(prior, std::vector<double>(6, -kInf), 1.0), 0.0);
  EXPECT_EQ(cl::adaptive_tempering_exponent(prior, std::vector<double>(6, -kInf), 0.7, 0.5), 0.7);
  // Prior mass on one particle: the increment exp(τℓ) is weighed under the prior.
  std::vector<double> skewed = {std::log(0.97), std::log(0.01), std::log(0.01), std::log(0.01)};
  const std::vector<double> same = {-1.0, -1.0, -1.0, -1.0};
  EXPECT_NEAR(cl::conditional_ess(skewed, same, 1.0), 4.0, 1e-9);
}

// ---- The see-through lost test ----

namespace {

using conicloc::test::vlp16;

}  // namespace

TEST(SeeThroughCheck, TruePoseSeesNoWallsFromWithinAndWrongPosesDo) {
  const auto map = ct::make_box_room();
  const cl::SeeThroughCheck check(map, vlp16(), cl::SeeThroughConfig{});
  std::mt19937_64 rng(2);
  ct::SyntheticScanOptions options;
  options.range_sigma_m = 0.03;
  const cl::Pose3 truth = cl::make_pose(2.5, 2.0, 1.2, 0.3);
  const auto scan = ct::make_scan(map, truth, options, rng);
  const cl::SeeThroughResult at_truth = check.evaluate(scan, truth);
  EXPECT_GT(at_truth.beams, 500u);
  EXPECT_LT(at_truth.fraction(), 0.01);
  // 3 m over and 90° turned (the kidnap of the issue), or 1.5 m off only: the far wall of the
  // measured scan lies behind a wall the wrong pose predicts.
  for (const cl::Pose3& wrong :
       {cl::make_pose(5.5, 2.0, 1.2, 0.3 + M_PI / 2), cl::make_pose(4.0, 3.0, 1.2, 0.3)}) {
    EXPECT_GT(check.evaluate(scan, wrong).fraction(), 0.1);
  }
}

TEST(SeeThroughCheck, ClutterIsShortAndNeverSeesThrough) {
  // Everything the map lacks stands in front of its walls: all-short returns count as nothing.
  const auto map = ct::make_box_room();
  const cl::SeeThroughCheck check(map, vlp16(), cl::SeeThroughConfig{});
  std::mt19937_64 rng(4);
  const cl::Pose3 truth = cl::make_pose(5.0, 4.0, 1.2, -1.0);
  auto scan = ct::make_scan(map, truth, ct::SyntheticScanOptions{}, rng);
  for (auto& ring : scan.rings) {
    for (auto& ret : ring.returns) ret.range_m = std::max(0.6, 0.5 * ret.range_m);
  }
  const cl::SeeThroughResult result = check.evaluate(scan, truth);
  EXPECT_GT(result.beams, 500u);
  EXPECT_EQ(result.see_through, 0u);
}

TEST(SeeThroughCheck, TrackingACleanRecordingNeverDeclaresItselfLost) {
  // A sensor walking through the box room, exact-ish ranges: the tracked estimate's returns stay
  // in front of the mapped surfaces, so the lost test stays quiet scan after scan.
  const auto map = ct::make_box_room();
  cl::LocalizerConfig config;
  config.filter.initial_particles = 300;
  config.filter.max_particles = 1500;
  config.motion.height_above_floor_m = 1.2;
  config.observation.conic_beam.beams.max_beams = 500;
  config.threads = 2;
  cl::Localizer localizer(map, vlp16(), config);
  const auto pose_at = [](int k) {
    const double t = 0.1 * k;
    return cl::make_pose(2.0 + 0.5 * t, 2.5 + 0.3 * std::sin(0.5 * t), 1.2, 0.2 + 0.1 * t);
  };
  cl::Vector6 sigma;
  sigma << 0.05, 0.05, 0.01, 0.005, 0.005, 0.02;
  localizer.initialise(pose_at(0), sigma);
  std::mt19937_64 rng(7);
  ct::SyntheticScanOptions options;
  options.range_sigma_m = 0.01;
  for (int k = 0; k < 30; ++k) {
    options.start_time_s = 0.1 * k;
    const auto r = localizer.update(ct::make_scan(map, pose_at(k), pose_at(k + 1), options, rng));
    EXPECT_FALSE(r.recovered) << k;
    EXPECT_LT(r.see_through_fraction, config.recovery.max_see_through_fraction / 2) << k;
    // A converged cloud is tempered to what the scan is worth: its beams grouped by surface.
    EXPECT_GT(r.effective_terms, 5.0) << k;
    EXPECT_LT(r.effective_terms, 0.2 * static_cast<double>(r.terms)) << k;
    EXPECT_DOUBLE_EQ(r.tempering, r.effective_terms / static_cast<double>(r.terms)) << k;
  }
}

// ---- Simulated captures of the example building (through the binary) ----

namespace {

struct Capture {
  fs::path dir;
  std::vector<conicloc::io::StampedPose> truth;
};

int run(const std::string& arguments, const fs::path& log) {
  return conicloc::test::run_conicloc(arguments, log);
}

// One column of a details CSV (header names the columns).

// Index of the first estimate from which every estimate stays within 0.2 m and 5° of the truth
// (the evaluate sweep's convergence), or −1.
int converged_from(const std::vector<conicloc::io::StampedPose>& estimate,
                   const std::vector<conicloc::io::StampedPose>& truth) {
  int from = -1;
  for (std::size_t k = 0; k < estimate.size(); ++k) {
    // Truth is one pose per scan start; the nearest one is within half a scan (≤ 5 cm here).
    std::size_t j = 0;
    for (std::size_t i = 1; i < truth.size(); ++i) {
      if (std::abs(truth[i].time_s - estimate[k].time_s) <
          std::abs(truth[j].time_s - estimate[k].time_s))
        j = i;
    }
    const cl::Pose3& t = truth[j].pose;
    const bool close = (estimate[k].pose.translation() - t.translation()).head<2>().norm() < 0.2 &&
                       std::abs(cl::angle_difference(cl::yaw_of(estimate[k].pose), cl::yaw_of(t))) <
                           5.0 * M_PI / 180.0;
    if (close && from < 0) from = static_cast<int>(k);
    if (!close) from = -1;
  }
  return from;
}

class ExampleBuilding : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("conicloc_global_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    ok_ = run("simulate --duration 7 --seed 1 --out " + (dir_ / "run.pcap").string() + " --truth " +
                  (dir_ / "truth.tum").string() + " --odom " + (dir_ / "odom.tum").string(),
              dir_ / "sim.log") == 0;
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  static std::string localize(const std::string& name, const std::string& start) {
    return "localize --pcap " + (dir_ / "run.pcap").string() + " --odom " +
           (dir_ / "odom.tum").string() + " " + start + " --out " +
           (dir_ / (name + ".tum")).string() + " --details " + (dir_ / (name + ".csv")).string();
  }
  static std::string init_at(const cl::Pose3& pose) {
    const Eigen::Vector3d t = pose.translation();
    return "--init " + std::to_string(t.x()) + "," + std::to_string(t.y()) + "," +
           std::to_string(t.z()) + "," + std::to_string(cl::yaw_of(pose) * 180.0 / M_PI);
  }

  static inline fs::path dir_;
  static inline bool ok_ = false;
};

}  // namespace

TEST_F(ExampleBuilding, GlobalLocalisationConvergesWithin50Scans) {
  ASSERT_TRUE(ok_);
  const auto truth = conicloc::io::read_tum((dir_ / "truth.tum").string());
  ASSERT_EQ(run(localize("global", "--global --particles 1500 --beams 200 --seed 2 --threads 2"),
                dir_ / "global.log"),
            0);
  const auto estimate = conicloc::io::read_tum((dir_ / "global.tum").string());
  ASSERT_GT(estimate.size(), 60u);
  const int from = converged_from(estimate, truth);
  ASSERT_GE(from, 0) << "never converged";
  EXPECT_LT(from, 50);  // issue #6
}

TEST_F(ExampleBuilding, KidnappedFilterNoticesAndRestartsGlobally) {
  // Started confidently (σ 0.1 m, 2°) 3 m off and turned 90°: its floor and ceiling beams fit, but
  // the walls it predicts stand in front of what the sensor measures. The see-through test fires
  // within a few scans and the set is refilled over the whole building.
  ASSERT_TRUE(ok_);
  const auto truth = conicloc::io::read_tum((dir_ / "truth.tum").string());
  const cl::Pose3 start = truth.front().pose;
  const Eigen::Vector3d t = start.translation();
  const cl::Pose3 kidnapped =
      cl::make_pose(t.x() + 3.0, t.y(), t.z(), cl::yaw_of(start) + M_PI / 2);
  ASSERT_EQ(run(localize("kidnap", init_at(kidnapped) +
                                       " --init-sigma 0.1,0.1,2 --init-particles 300"
                                       " --particles 600 --beams 150 --seed 2 --threads 2"),
                dir_ / "kidnap.log"),
            0);
  const auto recovered = conicloc::test::csv_column(dir_ / "kidnap.csv", "recovered");
  const auto see_through = conicloc::test::csv_column(dir_ / "kidnap.csv", "see_through_fraction");
  const auto particles = conicloc::test::csv_column(dir_ / "kidnap.csv", "particles");
  const auto spread = conicloc::test::csv_column(dir_ / "kidnap.csv", "spread_m");
  ASSERT_GT(recovered.size(), 10u);
  ASSERT_EQ(see_through.size(), recovered.size());
  int first_recovery = -1;
  for (std::size_t k = 0; k < recovered.size() && first_recovery < 0; ++k) {
    if (recovered[k] > 0.5) first_recovery = static_cast<int>(k);
  }
  ASSERT_GE(first_recovery, 0) << "the lost filter was never noticed";
  EXPECT_LE(first_recovery, 3);  // three scans of seeing through walls
  for (int k = 0; k <= first_recovery; ++k) EXPECT_GT(see_through[k], 0.1) << k;
  EXPECT_EQ(particles[first_recovery], 600.0);  // refilled to the maximum ...
  EXPECT_GT(spread[first_recovery + 1], 3.0);   // ... over the whole building
}

TEST_F(ExampleBuilding, TrackingOfACaptureWithClutterNeverDeclaresItselfLost) {
  // The default simulation holds furniture and people (short returns), map errors and range noise.
  ASSERT_TRUE(ok_);
  const auto truth = conicloc::io::read_tum((dir_ / "truth.tum").string());
  ASSERT_EQ(run(localize("track", init_at(truth.front().pose) +
                                      " --init-sigma 0.05,0.05,1 --init-particles 300"
                                      " --particles 1000 --beams 500 --seed 3 --threads 2"),
                dir_ / "track.log"),
            0);
  const auto recovered = conicloc::test::csv_column(dir_ / "track.csv", "recovered");
  ASSERT_GT(recovered.size(), 60u);
  for (std::size_t k = 0; k < recovered.size(); ++k) EXPECT_EQ(recovered[k], 0.0) << k;
  const auto estimate = conicloc::io::read_tum((dir_ / "track.tum").string());
  EXPECT_EQ(converged_from(estimate, truth), 0);
}
