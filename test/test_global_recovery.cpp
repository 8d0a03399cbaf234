// Global localisation and kidnap recovery: adaptive tempering (localizer/adaptive_tempering.hpp),
// the see-through lost test (localizer/models/see_through_check.hpp), and both on simulated
// captures of the shipped example building (simulated by the `conicloc` binary, localized through
// run/localize_run.hpp as `conicloc localize` does).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <vector>

#include "io/indoorgml.hpp"
#include "io/tum_trajectory.hpp"
#include "localizer/conic/pose.hpp"
#include "localizer/filter/adaptive_tempering.hpp"
#include "localizer/filter/localizer.hpp"
#include "localizer/filter/log_weights.hpp"
#include "localizer/models/see_through_check.hpp"
#include "run/localize_run.hpp"
#include "sensor/builtin_calibration.hpp"
#include "synthetic_room.hpp"
#include "test/cli_run.hpp"

namespace cl = conicloc::localizer;
namespace cr = conicloc::run;
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
  const cl::SeeThroughCheck check(map, vlp16(), cl::SeeThroughConfig{},
                                  cl::RangeSensor{}.max_range_m);
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

TEST(SeeThroughCheck, APillarTheMapPlacesOffIsNoEvidenceAgainstTheTruePose) {
  // The world's pillar stands 8 cm from where the map has it, the sensor 0.4 m from its corner:
  // beams that pass beside the real pillar hit the map's pillar near its silhouette, and reach
  // the far wall. They count only without the edge margins.
  auto world = ct::make_empty_room("room", {10, 6, 3});
  ct::add_box(world, 0, {7.08, 1.0, 0.0}, {8.08, 1.6, 3.0}, false);
  const auto map = ct::make_box_room();  // its pillar spans x 7.0 to 8.0
  std::mt19937_64 rng(3);
  ct::SyntheticScanOptions options;
  options.azimuth_step_rad = 0.2 * M_PI / 180.0;
  options.range_sigma_m = 0.01;
  const cl::Pose3 truth = cl::make_pose(6.7, 1.9, 1.2, 0.4);
  const auto scan = ct::make_scan(world, truth, options, rng);
  cl::SeeThroughConfig config;
  config.beams.max_beams = 5000;
  const cl::SeeThroughCheck check(map, vlp16(), config, cl::RangeSensor{}.max_range_m);
  cl::SeeThroughConfig sharp = config;
  sharp.edge_margin_m = 0.0;
  sharp.edge_margin_rad = 0.0;
  const cl::SeeThroughCheck sharp_check(map, vlp16(), sharp, cl::RangeSensor{}.max_range_m);
  const cl::SeeThroughResult with_margins = check.evaluate(scan, truth);
  const cl::SeeThroughResult without = sharp_check.evaluate(scan, truth);
  EXPECT_GT(without.see_through, 20u);
  EXPECT_EQ(with_margins.see_through, 0u);
  EXPECT_GT(with_margins.beams, without.beams * 9 / 10);
  // A wrong pose still sees through: the margins take only the beams near an edge.
  const cl::Pose3 wrong = cl::make_pose(4.0, 3.0, 1.2, 0.4);
  EXPECT_GT(check.evaluate(scan, wrong).fraction(), 0.1);
}

// Shared out as parts (the localizer's threads each predicting some of the rings), the check
// counts what it counts whole, at the truth and at wrong poses, for 1 to 5 parts, the parts run
// in any order.
TEST(SeeThroughCheck, PartsCountWhatTheWholeCounts) {
  const auto map = ct::make_box_room();
  const cl::SeeThroughCheck check(map, vlp16(), cl::SeeThroughConfig{},
                                  cl::RangeSensor{}.max_range_m);
  const cl::Pose3 truth = cl::make_pose(2.5, 2.0, 1.2, 0.3);
  const auto scan = ct::make_scan(map, truth, M_PI / 180.0, 0.03, 6);
  for (const cl::Pose3& pose : {truth, cl::make_pose(5.5, 2.0, 1.2, 0.3 + M_PI / 2),
                                cl::make_pose(4.0, 3.0, 1.2, 0.3, 0.02, -0.03)}) {
    const cl::SeeThroughResult whole = check.evaluate(scan, pose);
    for (int parts = 1; parts <= 5; ++parts) {
      cl::SeeThroughWork work;
      check.start(pose, parts, work);
      for (int s = parts - 1; s >= 0; --s) check.part(scan, s, work);
      const cl::SeeThroughResult shared = check.result(work);
      EXPECT_EQ(shared.beams, whole.beams) << parts << " parts";
      EXPECT_EQ(shared.see_through, whole.see_through) << parts << " parts";
    }
  }
}

TEST(SeeThroughCheck, ClutterIsShortAndNeverSeesThrough) {
  // Everything the map lacks stands in front of its walls: all-short returns count as nothing.
  const auto map = ct::make_box_room();
  const cl::SeeThroughCheck check(map, vlp16(), cl::SeeThroughConfig{},
                                  cl::RangeSensor{}.max_range_m);
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
    // Less only while the start's cloud is wider than the likelihood peak and would keep under
    // 5 % of its particles effective (ParticleFilterConfig::tracking_ess_fraction): the first
    // two scans here.
    EXPECT_GT(r.effective_terms, 5.0) << k;
    EXPECT_LT(r.effective_terms, 0.2 * static_cast<double>(r.terms)) << k;
    const double worth = r.effective_terms / static_cast<double>(r.terms);
    EXPECT_LE(r.tempering, worth) << k;
    if (k >= 2) {
      EXPECT_DOUBLE_EQ(r.tempering, worth) << k;
    }
  }
}

// ---- Simulated captures of the example building ----

namespace {

int run(const std::string& arguments, const fs::path& log) {
  return conicloc::test::run_conicloc(arguments, log);
}

// What a run gave at every localized scan.
struct Localized {
  std::vector<conicloc::io::StampedPose> estimate;
  std::vector<cl::UpdateResult> results;
};

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

  // `conicloc localize --pcap run.pcap --odom odom.tum` with `config`'s filter from `start`, on
  // two threads: the same run, through the run library.
  static Localized localize(const cl::LocalizerConfig& config, const cr::FilterStart& start) {
    const auto loaded = conicloc::io::load_indoorgml(CONICLOC_EXAMPLE_MAP);
    cr::LocalizeRunConfig run;
    run.pcap_path = (dir_ / "run.pcap").string();
    run.calibration = conicloc::sensor::builtin_calibration(conicloc::sensor::SensorModel::VLP16);
    run.localizer = config;
    run.localizer.threads = 2;
    run.localizer.motion.height_above_floor_m = 0.8;  // localize's --height
    run.two_sided_walls = loaded.report.two_sided_faces > 0;
    run.start = start;
    run.odometry = conicloc::io::read_tum((dir_ / "odom.tum").string());
    Localized localized;
    cr::run_localization(loaded.map, run, [&](double utc_s, const cl::UpdateResult& result) {
      localized.estimate.push_back({utc_s, result.pose});
      localized.results.push_back(result);
    });
    return localized;
  }
  // `--init` at `pose` (its position and yaw) with `--init-sigma` σ_xy (m), σ_yaw (degrees).
  static cr::FilterStart init_at(const cl::Pose3& pose, double sigma_xy_m, double sigma_yaw_deg) {
    const Eigen::Vector3d t = pose.translation();
    cr::FilterStart start;
    start.pose = cl::make_pose(t.x(), t.y(), t.z(), cl::yaw_of(pose));
    start.sigma << sigma_xy_m, sigma_xy_m, 0.02, 0.01, 0.01, sigma_yaw_deg * M_PI / 180.0;
    return start;
  }
  static cl::LocalizerConfig filter(std::size_t initial_particles, std::size_t particles,
                                    std::size_t beams, std::uint64_t seed) {
    cl::LocalizerConfig config;
    config.filter.initial_particles = initial_particles;
    config.filter.max_particles = particles;
    config.observation.conic_beam.beams.max_beams = beams;
    config.seed = seed;
    return config;
  }

  static inline fs::path dir_;
  static inline bool ok_ = false;
};

}  // namespace

TEST_F(ExampleBuilding, GlobalLocalisationConvergesWithin50Scans) {
  ASSERT_TRUE(ok_);
  const auto truth = conicloc::io::read_tum((dir_ / "truth.tum").string());
  cr::FilterStart global;
  global.global = true;
  const auto estimate =
      localize(filter(cl::LocalizerConfig{}.filter.initial_particles, 1500, 200, 2), global)
          .estimate;
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
  const auto results = localize(filter(300, 600, 150, 2), init_at(kidnapped, 0.1, 2.0)).results;
  ASSERT_GT(results.size(), 10u);
  int first_recovery = -1;
  for (std::size_t k = 0; k < results.size() && first_recovery < 0; ++k) {
    if (results[k].recovered) first_recovery = static_cast<int>(k);
  }
  ASSERT_GE(first_recovery, 0) << "the lost filter was never noticed";
  EXPECT_LE(first_recovery, 3);  // three scans of seeing through walls
  for (int k = 0; k <= first_recovery; ++k) EXPECT_GT(results[k].see_through_fraction, 0.1) << k;
  EXPECT_EQ(results[first_recovery].particles, 600u);    // refilled to the maximum ...
  EXPECT_GT(results[first_recovery + 1].spread_m, 3.0);  // ... over the whole building
}

TEST_F(ExampleBuilding, TrackingOfACaptureWithClutterNeverDeclaresItselfLost) {
  // The default simulation holds furniture and people (short returns), map errors and range noise.
  ASSERT_TRUE(ok_);
  const auto truth = conicloc::io::read_tum((dir_ / "truth.tum").string());
  const auto track = localize(filter(300, 1000, 500, 3), init_at(truth.front().pose, 0.05, 1.0));
  ASSERT_GT(track.results.size(), 60u);
  for (std::size_t k = 0; k < track.results.size(); ++k)
    EXPECT_FALSE(track.results[k].recovered) << k;
  EXPECT_EQ(converged_from(track.estimate, truth), 0);
}
