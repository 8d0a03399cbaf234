// The localizer on synthetic scans of a box room (own ray cast): observation models, tracking,
// global localisation, repeatability, and the stiff cases of DESIGN.md.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>

#include "localizer/filter/localizer.hpp"
#include "localizer/filter/log_weights.hpp"
#include "localizer/models/point_to_plane_model.hpp"
#include "sensor/builtin_calibration.hpp"
#include "model_test_name.hpp"
#include "synthetic_room.hpp"

namespace cl = conicloc::localizer;
namespace ct = conicloc::test;
using conicloc::sensor::Scan;

namespace {

using conicloc::test::vlp16;

cl::LocalizerConfig small_config(const std::string& model) {
  cl::LocalizerConfig config;
  config.observation.model = model;
  config.filter.initial_particles = 300;
  config.filter.min_particles = 150;
  config.filter.max_particles = 1500;
  config.motion.height_above_floor_m = 1.2;
  config.threads = 2;
  config.seed = 5;
  return config;
}

double position_error(const cl::Pose3& a, const cl::Pose3& b) {
  return (a.translation() - b.translation()).head<2>().norm();
}
double yaw_error_deg(const cl::Pose3& a, const cl::Pose3& b) {
  return std::abs(cl::angle_difference(cl::yaw_of(a), cl::yaw_of(b))) * 180.0 / M_PI;
}

// The sensor walks along a gentle curve through the room at ~0.5 m/s, 10 scans per second.
cl::Pose3 path_pose(int scan) {
  const double t = 0.1 * scan;
  return cl::make_pose(2.0 + 0.5 * t, 2.5 + 0.3 * std::sin(0.5 * t), 1.2, 0.2 + 0.1 * t);
}

// A hand-held sensor's sway along the path: roll and pitch swing ±2° at 2.5 rad/s.
double sway_roll_at(double t) {
  return 2.0 * M_PI / 180.0 * std::sin(2.5 * t);
}
double sway_pitch_at(double t) {
  return 2.0 * M_PI / 180.0 * std::cos(2.5 * t);
}
cl::Pose3 swaying_pose(int scan) {
  const double t = 0.1 * scan;
  return path_pose(scan) * cl::make_pose(0.0, 0.0, 0.0, 0.0, sway_pitch_at(t), sway_roll_at(t));
}

struct PathRun {
  std::vector<cl::UpdateResult> results;
  std::vector<cl::Pose3> truth;
};

PathRun run_path(const conicloc::maps::PlaneMap& map, cl::Localizer& localizer, int scans,
                 double noise_m, std::uint64_t scan_seed = 9) {
  std::mt19937_64 rng(scan_seed);
  ct::SyntheticScanOptions options;
  options.range_sigma_m = noise_m;
  PathRun run;
  for (int k = 0; k < scans; ++k) {
    options.start_time_s = 0.1 * k;
    const Scan scan = ct::make_scan(map, path_pose(k), path_pose(k + 1), options, rng);
    run.results.push_back(localizer.update(scan));
    run.truth.push_back(path_pose(k + 1));  // the estimate is at the scan's end
  }
  return run;
}

}  // namespace

TEST(PointToPlaneModel, DistanceToMapIsThePlaneDistanceInsidePolygons) {
  const auto map = ct::make_box_room();
  cl::PointToPlaneModel model(map, cl::RangeSensor{}, cl::PointToPlaneConfig{});
  EXPECT_NEAR(model.distance_to_map({3.0, 1.0, 1.5}), 1.0, 1e-9);    // nearest: the wall y = 0
  EXPECT_NEAR(model.distance_to_map({0.3, 3.0, 1.5}), 0.3, 1e-9);    // wall x = 0
  EXPECT_NEAR(model.distance_to_map({6.9, 1.3, 1.0}), 0.1, 1e-9);    // pillar face x = 7
  EXPECT_NEAR(model.distance_to_map({5.0, 3.0, 2.99}), 0.01, 1e-9);  // ceiling
  EXPECT_NEAR(model.distance_to_map({5.0, 3.0, 50.0}), 2.0, 1e-12);  // clipped at max_distance_m
}

class EveryModel : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryModel, TruePoseScoresBestAmongNearbyPoses) {
  const auto map = ct::make_box_room();
  auto config = small_config(GetParam());
  const auto model = cl::make_observation_model(config.observation, map, vlp16());
  EXPECT_EQ(model->name(), GetParam());
  std::mt19937_64 rng(1);
  ct::SyntheticScanOptions options;
  options.range_sigma_m = 0.01;
  const cl::Pose3 truth = cl::make_pose(3.0, 2.5, 1.2, 0.4);
  model->prepare(ct::make_scan(map, truth, options, rng),
                 Eigen::AlignedBox3d(Eigen::Vector3d(2, 1.5, 1), Eigen::Vector3d(4, 3.5, 1.4)));
  ASSERT_GT(model->term_count(), 10u);
  auto scratch = model->make_scratch();
  const auto at_truth = model->score(truth, scratch.get());
  EXPECT_GT(at_truth.inlier_fraction, 0.9);
  for (const cl::Pose3& other :
       {cl::make_pose(3.1, 2.5, 1.2, 0.4), cl::make_pose(3.0, 2.4, 1.2, 0.4),
        cl::make_pose(3.0, 2.5, 1.2, 0.43), cl::make_pose(3.0, 2.5, 1.2, 0.37),
        cl::make_pose(3.05, 2.55, 1.2, 0.41)}) {
    const auto score = model->score(other, scratch.get());
    EXPECT_LT(score.log_likelihood, at_truth.log_likelihood);
    EXPECT_TRUE(std::isfinite(score.log_likelihood));
  }
  // Far off (other side of the room, turned): finite, and much worse.
  const auto far = model->score(cl::make_pose(8.5, 4.5, 1.2, 2.5), scratch.get());
  EXPECT_TRUE(std::isfinite(far.log_likelihood));
  EXPECT_LT(far.inlier_fraction, 0.5);
}

// Tracking runs as its own suite so that a model failing the bound can be disabled visibly.
class Tracking : public ::testing::TestWithParam<std::string> {};

TEST_P(Tracking, TracksAMovingSensorWithin5cmAndHalfADegree) {
  const auto map = ct::make_box_room();
  cl::Localizer localizer(map, vlp16(), small_config(GetParam()));
  cl::Vector6 sigma;
  sigma << 0.1, 0.1, 0.01, 0.005, 0.005, 2.0 * M_PI / 180.0;
  // Start 8 cm and 1.5° off the true pose.
  localizer.initialise(path_pose(0) * cl::make_pose(0.06, -0.05, 0.0, 0.026), sigma);
  const PathRun run = run_path(map, localizer, 30, 0.01);
  for (std::size_t k = 10; k < run.results.size(); ++k) {
    EXPECT_LT(position_error(run.results[k].pose, run.truth[k]), 0.05) << "scan " << k;
    EXPECT_LT(yaw_error_deg(run.results[k].pose, run.truth[k]), 0.5) << "scan " << k;
    EXPECT_NEAR(run.results[k].pose.translation().z(), 1.2, 0.05);
    EXPECT_FALSE(run.results[k].recovered);
    EXPECT_EQ(run.results[k].status, cl::LocalizerStatus::Tracking) << "scan " << k;
  }
}

INSTANTIATE_TEST_SUITE_P(Models, Tracking, ::testing::Values("conic-beam", "point-to-plane"),
                         conicloc::test::model_test_name);
// conic-segment once exceeded the 0.5° bound here (0.51° on scan 18): each segment counted as 10
// beams, so a scan weighed 3.4× the filter's tempering cap and the cloud collapsed to one
// particle per scan. Its terms are now the returns its segments summarise.
INSTANTIATE_TEST_SUITE_P(ConicSegment, Tracking, ::testing::Values("conic-segment"),
                         conicloc::test::model_test_name);

INSTANTIATE_TEST_SUITE_P(Models, EveryModel,
                         ::testing::Values("conic-beam", "conic-segment", "point-to-plane"),
                         conicloc::test::model_test_name);

// A hand-held sensor sways: roll and pitch swing by ±2° at 0.4 Hz (up to 0.5° per scan) while it
// walks the path. The tilt measured from each scan (scan_tilt.hpp) follows the swing; the
// mounting model alone (tilt measurement off) keeps the particles near level and misses it by
// degrees. The measured tilt is the one that explains the whole rotation best, compared with the
// tilt halfway through it (the ring-form de-skew keeps every return on its ring's cone). Roll
// is seen weakly here: the side walls, 2.5 m and 3.5 m away, hide the floor and the ceiling
// sideways, so a roll moves the side returns only by d·tan(φ)·Δroll (5 mm at 2 m for 15° and
// 0.6°); pitch is seen sharply along the room. Hence 0.8°, against 2° unmeasured.
TEST(Localizer, FollowsTheTiltOfASwayingSensor) {
  const auto map = ct::make_box_room();
  struct Run {
    double worst_tilt_error_deg = 0.0;
    double least_inlier_fraction = 1.0;
  };
  const auto run_swaying = [&](bool measure_tilt) {
    cl::LocalizerConfig config = small_config("conic-beam");
    config.scan_tilt.enabled = measure_tilt;
    cl::Localizer localizer(map, vlp16(), config);
    cl::Vector6 sigma;
    sigma << 0.05, 0.05, 0.01, 0.005, 0.005, 1.0 * M_PI / 180.0;
    localizer.initialise(path_pose(0), sigma);
    std::mt19937_64 rng(9);
    ct::SyntheticScanOptions options;
    options.range_sigma_m = 0.01;
    Run run;
    for (int k = 0; k < 25; ++k) {
      options.start_time_s = 0.1 * k;
      const auto result =
          localizer.update(ct::make_scan(map, swaying_pose(k), swaying_pose(k + 1), options, rng));
      EXPECT_LT(position_error(result.pose, swaying_pose(k + 1)), 0.05) << "scan " << k;
      const cl::PoseState estimate = cl::pose_state_from(result.pose);
      const double mid_t = 0.1 * k + 0.05;
      // From the third scan: the first is weighed before any tilt was measured.
      if (k >= 2) {
        run.worst_tilt_error_deg = std::max(
            {run.worst_tilt_error_deg, std::abs(estimate.roll - sway_roll_at(mid_t)) * 180.0 / M_PI,
             std::abs(estimate.pitch - sway_pitch_at(mid_t)) * 180.0 / M_PI});
        run.least_inlier_fraction = std::min(run.least_inlier_fraction, result.inlier_fraction);
      }
    }
    return run;
  };
  const Run measured = run_swaying(true);
  const Run mounting = run_swaying(false);
  EXPECT_LT(measured.worst_tilt_error_deg, 0.8);
  EXPECT_GT(mounting.worst_tilt_error_deg, 1.5);
  EXPECT_GT(measured.least_inlier_fraction, mounting.least_inlier_fraction);
}

// A start wider than one tracked peak is searched (spread over 0.25 m) but is one hypothesis: its
// tilt is measured from the first scans, as a tracked cloud's is, and judged by what a scan is
// worth (τ_max), not by the smaller exponent the search weighs it with. Levelled only once the
// start had settled, a hand-held sensor's sway took the true pose's inliers under the lost test's
// bound first (PNU, seed 4).
TEST(Localizer, AWideStartIsLevelledToTheScanWhileItIsStillSearched) {
  const auto map = ct::make_box_room();
  cl::Localizer localizer(map, vlp16(), small_config("conic-beam"));
  localizer.initialise(path_pose(0),
                       (cl::Vector6() << 0.4, 0.4, 0.01, 0.005, 0.005, 0.087).finished());
  std::mt19937_64 rng(9);
  ct::SyntheticScanOptions options;
  options.range_sigma_m = 0.01;
  const auto first =
      localizer.update(ct::make_scan(map, swaying_pose(0), swaying_pose(1), options, rng));
  ASSERT_GT(first.spread_m, 0.25);  // the second scan is levelled at a cloud still searched
  options.start_time_s = 0.1;
  const auto second =
      localizer.update(ct::make_scan(map, swaying_pose(1), swaying_pose(2), options, rng));
  const cl::PoseState estimate = cl::pose_state_from(second.pose);
  // Left level, the pitch would be 1.9° off here (1.5° as the cloud's mean).
  EXPECT_LT(std::abs(estimate.roll - sway_roll_at(0.15)) * 180.0 / M_PI, 0.8);
  EXPECT_LT(std::abs(estimate.pitch - sway_pitch_at(0.15)) * 180.0 / M_PI, 0.8);
}

TEST(Localizer, GlobalLocalisationConvergesInTheAsymmetricRoom) {
  const auto map = ct::make_box_room();
  auto config = small_config("conic-beam");
  config.filter.max_particles = 4000;
  config.observation.conic_beam.beams.max_beams = 500;
  cl::Localizer localizer(map, vlp16(), config);
  localizer.initialise_global();
  EXPECT_EQ(localizer.particles().size(), 4000u);
  const PathRun run = run_path(map, localizer, 60, 0.02);
  int first_converged = -1;  // from this scan on, every estimate is within 10 cm and 2°
  for (std::size_t k = 0; k < run.results.size(); ++k) {
    const bool close = position_error(run.results[k].pose, run.truth[k]) < 0.1 &&
                       yaw_error_deg(run.results[k].pose, run.truth[k]) < 2.0;
    if (close && first_converged < 0) first_converged = static_cast<int>(k);
    if (!close) first_converged = -1;
  }
  ASSERT_GE(first_converged, 0) << "never converged";
  EXPECT_LT(first_converged, 50);  // issue #6: global converging within 50 scans
  // The status says what the filter knows: not sure over the whole room at first, tracking at
  // the end; its covariance is wide first and tight at the end.
  EXPECT_EQ(run.results.front().status, cl::LocalizerStatus::Uncertain);
  EXPECT_GT(run.results.front().spread_m, 1.0);
  EXPECT_EQ(run.results.back().status, cl::LocalizerStatus::Tracking);
  // While it searches the room it scores 4 rings (search_rings.hpp), then all 16.
  EXPECT_EQ(run.results.front().rings_scored, 4U);
  EXPECT_EQ(run.results.back().rings_scored, 16U);
  EXPECT_LT(run.results.back().covariance(0, 0) + run.results.back().covariance(1, 1), 0.01);
  EXPECT_LT(run.results.back().particles, 4000u);  // KLD shrank the set once converged
}

namespace {

// The share of a global start's particles after its first scan (of run_path's path) that
// `near(particle, truth)` accepts; `configure` sets the config's proposals.
double share_after_first_global_scan(
    const std::function<void(cl::LocalizerConfig&)>& configure,
    const std::function<bool(const cl::Particle&, const cl::Pose3&)>& near) {
  const auto map = ct::make_box_room();
  auto config = small_config("conic-beam");
  config.filter.max_particles = 2000;
  configure(config);
  cl::Localizer localizer(map, vlp16(), config);
  localizer.initialise_global();
  const PathRun run = run_path(map, localizer, 1, 0.02);
  int count = 0;
  for (const cl::Particle& p : localizer.particles()) count += near(p, run.truth.front());
  return static_cast<double>(count) / static_cast<double>(localizer.particles().size());
}

}  // namespace

TEST(Localizer, AGlobalStartTakesItsHeadingsFromTheFirstScan) {
  // The box room's walls run along x and y: the first scan's walls leave four headings, the true
  // one among them (heading_proposal.hpp). Counted after the first update, in particles within
  // 3° of one of them.
  const auto near_true_heading = [](double uniform_fraction) {
    return share_after_first_global_scan(
        [&](cl::LocalizerConfig& config) {
          config.headings.uniform_fraction = uniform_fraction;
          config.plan_search.fraction = 0.0;  // the headings alone
        },
        [](const cl::Particle& p, const cl::Pose3& truth) {
          const double off = std::remainder(p.state.yaw - cl::yaw_of(truth), M_PI / 2.0);
          return std::abs(off) < 3.0 * M_PI / 180.0;
        });
  };
  const double proposed = near_true_heading(0.5);
  const double uniform = near_true_heading(1.0);
  // Drawn: half proposed (σ 2°) plus the uniform half's share, 0.53; after the first scan's
  // selection 0.42–0.50 over config seeds 1–12 (mean 0.46; a position's four headings are drawn
  // together, headings_per_position). Uniform draws alone give 4 × 6° of 360°, 0.07.
  EXPECT_GT(proposed, 0.40);
  EXPECT_LT(uniform, 0.15);  // give or take the first scan's selection
}

TEST(Localizer, AGlobalStartDrawsPartOfItsParticlesWhereTheFirstScanFitsThePlan) {
  // plan_search.hpp: after the first scan, half of the particles stand about the poses where
  // the scan's walls fit the plan's, the truth first among them in the asymmetric room.
  const auto near_truth = [](double fraction) {
    return share_after_first_global_scan(
        [&](cl::LocalizerConfig& config) { config.plan_search.fraction = fraction; },
        [](const cl::Particle& p, const cl::Pose3& truth) {
          return position_error(p.state.to_pose(), truth) < 0.3 &&
                 yaw_error_deg(p.state.to_pose(), truth) < 3.0;
        });
  };
  const double with_plan = near_truth(0.5);
  EXPECT_GT(with_plan, 0.05) << with_plan << " vs " << near_truth(0.0);
  EXPECT_LT(near_truth(0.0), 0.01);  // 0.3 m and 3° of a 60 m² room, a quarter of the headings
  // By default every particle is drawn about the candidates: more of them about the truth.
  EXPECT_EQ(cl::PlanSearchConfig{}.fraction, 1.0);
  EXPECT_GT(near_truth(1.0), 1.5 * with_plan);
}

TEST(Localizer, AGlobalStartDrawnAboutItsCandidatesTakesTheParticlesTheyNeed) {
  // Each candidate gets the share it would have at the most candidates the search gives: 2,000
  // particles over 64 candidates, 31 each. Counted after the first scan, without resampling.
  const auto count_after_first_scan = [](const conicloc::maps::PlaneMap& map, double fraction) {
    auto config = small_config("conic-beam");
    config.filter.max_particles = 2000;
    config.filter.min_particles = 10;
    config.filter.resample_ess_fraction = 0.0;
    config.plan_search.fraction = fraction;
    cl::Localizer localizer(map, vlp16(), config);
    localizer.initialise_global();
    run_path(map, localizer, 1, 0.02);
    return localizer.particles().size();
  };
  const std::size_t per_candidate = 2000 / cl::PlanSearchConfig{}.max_candidates;
  ASSERT_EQ(per_candidate, 31u);
  const auto box_room = ct::make_box_room();
  const std::size_t drawn = count_after_first_scan(box_room, 1.0);
  EXPECT_EQ(drawn % per_candidate, 0u) << drawn;
  EXPECT_GE(drawn, per_candidate);
  EXPECT_LT(drawn, 2000u);
  // Half uniform: the uniform half needs the whole budget.
  EXPECT_EQ(count_after_first_scan(box_room, 0.5), 2000u);
  // The symmetric room fits the scan at two poses at least: twice the share, at least.
  auto symmetric = ct::make_box_room();
  symmetric.polygons.resize(6);
  symmetric.cells[0].polygons.resize(6);
  const std::size_t two = count_after_first_scan(symmetric, 1.0);
  EXPECT_EQ(two % per_candidate, 0u) << two;
  EXPECT_GE(two, 2 * per_candidate);
}

namespace {

// Two copies of the box room 60 m apart: a global start holds two modes 60 m apart.
conicloc::maps::PlaneMap two_rooms() {
  conicloc::maps::PlaneMap map = ct::make_box_room();
  conicloc::maps::Cell cell = map.cells[0];
  cell.id = "far room";
  cell.polygons.clear();
  for (auto& v : cell.footprint) v.x() += 60.0;
  cell.bounds.translate(Eigen::Vector3d(60.0, 0.0, 0.0));
  cell.representative_point.x() += 60.0;
  map.cells.push_back(cell);
  ct::add_box(map, 1, {60, 0, 0}, {70, 6, 3}, true);
  ct::add_box(map, 1, {67.0, 1.0, 0.0}, {68.0, 1.6, 3.0}, false);
  return map;
}

}  // namespace

TEST(Localizer, AGlobalStartsModesAreNotRoughenedByTheDistanceBetweenThem) {
  // Roughening jitters by a share of the cloud's extent, one mode's width in a tracked cloud;
  // a restart's cloud, 70 m across here, would jitter every particle by ~0.6 m and every mode
  // apart. With motion without noise and a sensor standing still, a resampled copy stays where
  // its parent was (the few leaders refined onto their peaks aside).
  const auto map = two_rooms();
  auto config = small_config("conic-beam");
  config.motion = ct::noiseless_motion(1.2);
  // Places added from later scans (missing_hypotheses.hpp, off by default) are new particles by
  // design: off here whatever the default.
  config.missing_hypotheses.every_scans = 0;
  cl::Localizer localizer(map, vlp16(), config);
  localizer.initialise_global();
  std::mt19937_64 rng(3);
  ct::SyntheticScanOptions options;
  options.range_sigma_m = 0.02;
  const cl::Pose3 standing = cl::make_pose(3.0, 2.5, 1.2, 0.4);
  cl::ParticleSet previous;
  int compared = 0;
  for (int k = 0; k < 12; ++k) {
    options.start_time_s = 0.1 * k;
    const cl::UpdateResult result =
        localizer.update(ct::make_scan(map, standing, options, rng), cl::Pose3::Identity());
    if (result.status == cl::LocalizerStatus::Tracking) break;
    if (!previous.empty()) {
      int moved = 0;
      for (const cl::Particle& p : localizer.particles()) {
        double nearest = std::numeric_limits<double>::infinity();
        for (const cl::Particle& q : previous)
          nearest = std::min(nearest, std::hypot(p.state.x - q.state.x, p.state.y - q.state.y));
        if (nearest > 0.2) ++moved;
      }
      EXPECT_LT(moved, static_cast<int>(localizer.particles().size()) / 20) << "scan " << k;
      ++compared;
    }
    previous = result.resampled ? localizer.particles() : cl::ParticleSet{};
  }
  EXPECT_GE(compared, 2);
}

TEST(Localizer, AStartWideEnoughToBeSearchedTakesTheFullParticleCount) {
  // small_config: 300 initial, 1,500 at most. 5 cm about the pose is one tracked peak; 0.2 m per
  // axis (xy std. dev. 0.28 m) is searched, and would be resampled to 1,500 copies of 300 draws.
  const auto map = ct::make_box_room();
  cl::Localizer localizer(map, vlp16(), small_config("conic-beam"));
  const cl::Pose3 start = path_pose(0);
  localizer.initialise(start, (cl::Vector6() << 0.05, 0.05, 0, 0, 0, 0.02).finished());
  EXPECT_EQ(localizer.particles().size(), 300u);
  localizer.initialise(start, (cl::Vector6() << 0.2, 0.2, 0, 0, 0, 0.087).finished());
  EXPECT_EQ(localizer.particles().size(), 1500u);
}

TEST(Localizer, StatusNamesAreTheDocumentedOnes) {
  EXPECT_STREQ(cl::status_name(cl::LocalizerStatus::Tracking), "tracking");
  EXPECT_STREQ(cl::status_name(cl::LocalizerStatus::Uncertain), "uncertain");
  EXPECT_STREQ(cl::status_name(cl::LocalizerStatus::Lost), "lost");
  EXPECT_STREQ(cl::status_name(cl::LocalizerStatus::Relocalizing), "relocalizing");
}

// Kidnapped while tracking: the filter says `lost` on the scan it refills the set, then
// `relocalizing` until it has converged again, and then `tracking` at the true pose.
TEST(Localizer, StatusAfterAKidnapIsLostThenRelocalizingThenTracking) {
  const auto map = ct::make_box_room();
  auto config = small_config("conic-beam");
  config.filter.max_particles = 4000;
  config.observation.conic_beam.beams.max_beams = 500;
  cl::Localizer localizer(map, vlp16(), config);
  cl::Vector6 sigma;
  sigma << 0.05, 0.05, 0.01, 0.005, 0.005, 1.0 * M_PI / 180.0;
  // Confident at a pose 2.5 m and 90° away from the truth.
  localizer.initialise(path_pose(0) * cl::make_pose(-1.0, 2.0, 0.0, M_PI / 2), sigma);
  const PathRun run = run_path(map, localizer, 60, 0.02);
  std::size_t lost = run.results.size(), tracking = run.results.size();
  for (std::size_t k = 0; k < run.results.size(); ++k) {
    if (run.results[k].status == cl::LocalizerStatus::Lost && lost == run.results.size()) lost = k;
    if (lost < k && run.results[k].status == cl::LocalizerStatus::Tracking) {
      tracking = k;
      break;
    }
  }
  ASSERT_LT(lost, 10u) << "the kidnap was not noticed";
  EXPECT_TRUE(run.results[lost].recovered);
  ASSERT_LT(tracking, run.results.size()) << "never tracking again";
  // In between, relocalizing (or lost again, when a restart over the whole building follows).
  for (std::size_t k = lost + 1; k < tracking; ++k) {
    EXPECT_TRUE(run.results[k].status == cl::LocalizerStatus::Relocalizing ||
                run.results[k].status == cl::LocalizerStatus::Lost)
        << "scan " << k << ": " << cl::status_name(run.results[k].status);
  }
  EXPECT_LT(position_error(run.results.back().pose, run.truth.back()), 0.1);
  EXPECT_EQ(run.results.back().status, cl::LocalizerStatus::Tracking);
}

TEST(Localizer, ThePersistentSeeThroughAloneNoticesAWrongPose) {
  // The per-scan tests switched off (no inlier bound, no single scan sees through enough): only
  // the see-through history over its window can raise the alarm, and it does once the window is
  // covered, not before.
  const auto map = ct::make_box_room();
  auto config = small_config("conic-beam");
  config.filter.max_particles = 4000;
  config.observation.conic_beam.beams.max_beams = 500;
  config.recovery.min_inlier_fraction = 0.0;
  config.recovery.max_see_through_fraction = 1.0;
  config.recovery.see_through_history.window_s = 1.0;
  cl::Localizer localizer(map, vlp16(), config);
  cl::Vector6 sigma;
  sigma << 0.05, 0.05, 0.01, 0.005, 0.005, 1.0 * M_PI / 180.0;
  localizer.initialise(path_pose(0) * cl::make_pose(-1.0, 2.0, 0.0, M_PI / 2), sigma);
  const PathRun run = run_path(map, localizer, 40, 0.02);
  std::size_t lost = run.results.size();
  for (std::size_t k = 0; k < run.results.size(); ++k) {
    if (run.results[k].recovered) {
      lost = k;
      break;
    }
  }
  // The window (1 s = 10 scan steps) is covered at the 11th scan (index 10) at the earliest; the
  // alarm needs lost_scans in a row from there.
  EXPECT_GE(lost, 10u + static_cast<std::size_t>(config.recovery.lost_scans) - 1u);
  EXPECT_LT(lost, 10u + static_cast<std::size_t>(config.recovery.lost_scans) + 5u);
  EXPECT_LT(position_error(run.results.back().pose, run.truth.back()), 0.1);
}

TEST(Localizer, RepeatsExactlyWithTheSameSeedForAnyThreadCount) {
  const auto map = ct::make_box_room();
  cl::Vector6 sigma;
  sigma << 0.2, 0.2, 0.01, 0.005, 0.005, 0.05;
  std::vector<std::vector<cl::UpdateResult>> runs;
  for (const int threads : {1, 2, 3}) {
    auto config = small_config("conic-beam");
    config.threads = threads;
    cl::Localizer localizer(map, vlp16(), config);
    localizer.initialise(path_pose(0), sigma);
    runs.push_back(run_path(map, localizer, 8, 0.02).results);
  }
  for (std::size_t r = 1; r < runs.size(); ++r) {
    for (std::size_t k = 0; k < runs[0].size(); ++k) {
      EXPECT_TRUE(runs[r][k].pose.isApprox(runs[0][k].pose, 0.0)) << "run " << r << " scan " << k;
      EXPECT_EQ(runs[r][k].particles, runs[0][k].particles);
      EXPECT_EQ(runs[r][k].log_likelihood, runs[0][k].log_likelihood);
    }
  }
  // A different seed gives a different (but still valid) run.
  auto config = small_config("conic-beam");
  config.seed = 6;
  cl::Localizer other(map, vlp16(), config);
  other.initialise(path_pose(0), sigma);
  const auto different = run_path(map, other, 8, 0.02).results;
  EXPECT_FALSE(different.back().pose.isApprox(runs[0].back().pose, 0.0));
}

namespace {

// Runs `config` on the box-room path with 1 and 3 threads from a cloud spanning many association
// grid cells (±20 cm, ±3°) and expects the same poses, particle counts and likelihoods bit for bit.
void expect_same_for_any_thread_count(cl::LocalizerConfig config) {
  const auto map = ct::make_box_room();
  cl::Vector6 sigma;
  sigma << 0.2, 0.2, 0.01, 0.005, 0.005, 0.05;
  std::vector<std::vector<cl::UpdateResult>> runs;
  for (const int threads : {1, 3}) {
    config.threads = threads;
    cl::Localizer localizer(map, vlp16(), config);
    localizer.initialise(path_pose(0), sigma);
    runs.push_back(run_path(map, localizer, 6, 0.02).results);
  }
  for (std::size_t k = 0; k < runs[0].size(); ++k) {
    EXPECT_TRUE(runs[1][k].pose.isApprox(runs[0][k].pose, 0.0)) << "scan " << k;
    EXPECT_EQ(runs[1][k].particles, runs[0][k].particles);
    EXPECT_EQ(runs[1][k].log_likelihood, runs[0][k].log_likelihood);
  }
}

}  // namespace

TEST(Localizer, ConicSegmentRepeatsExactlyForAnyThreadCount) {
  // Its per-thread association caches hold the association of each grid cell's centre, so which
  // particles a thread scored first changes nothing.
  expect_same_for_any_thread_count(small_config("conic-segment"));
}

TEST(Localizer, ConicBeamRepeatsExactlyForAnyThreadCount) {
  // conic-beam's per-thread caches hold the beam association of each grid cell's centre, so which
  // particles a thread scored first changes nothing.
  auto config = small_config("conic-beam");
  config.observation.shortcuts.association_grid = true;
  expect_same_for_any_thread_count(config);
}

TEST(Localizer, ConicBeamFullPredictionPerParticleTracks) {
  // The per-particle full prediction (association_grid = false), kept as the grid's reference:
  // the same tracking bounds as Tracking/conic_beam.
  const auto map = ct::make_box_room();
  auto config = small_config("conic-beam");
  config.observation.shortcuts.association_grid = false;
  cl::Localizer localizer(map, vlp16(), config);
  cl::Vector6 sigma;
  sigma << 0.1, 0.1, 0.01, 0.005, 0.005, 2.0 * M_PI / 180.0;
  localizer.initialise(path_pose(0) * cl::make_pose(0.06, -0.05, 0.0, 0.026), sigma);
  const PathRun run = run_path(map, localizer, 20, 0.01);
  for (std::size_t k = 10; k < run.results.size(); ++k) {
    EXPECT_LT(position_error(run.results[k].pose, run.truth[k]), 0.05) << "scan " << k;
    EXPECT_LT(yaw_error_deg(run.results[k].pose, run.truth[k]), 0.5) << "scan " << k;
  }
}

// ---- Stiff cases (DESIGN.md "Numerical stability") ----

TEST(StiffCases, TinyRangeNoiseWithThousandsOfBeams) {
  // σ = 1 mm ranges, 5760 beams all scored, no tempering: log-likelihood differences of 10³–10⁴
  // nats between particles; every weight but one underflows in the linear domain.
  const auto map = ct::make_box_room();
  auto config = small_config("conic-beam");
  config.observation.conic_beam.beams.max_beams = 0;
  config.filter.tempering = 1.0;
  config.filter.reference_terms = 0.0;                   // no cap
  config.filter.tracking_ess_fraction = 0.0;             // nor a floor of effective particles
  config.observation.sensor.noise.shared_sigma_m = 0.0;  // every explained beam counts
  cl::Localizer localizer(map, vlp16(), config);
  cl::Vector6 sigma;
  sigma << 0.1, 0.1, 0.01, 0.005, 0.005, 0.03;
  localizer.initialise(path_pose(0), sigma);
  const PathRun run = run_path(map, localizer, 12, 0.001);
  EXPECT_GT(run.results.front().terms, 5000u);
  for (std::size_t k = 0; k < run.results.size(); ++k) {
    const auto& r = run.results[k];
    EXPECT_GT(r.tempering, 0.5) << k;  // the stiff case it is meant to be
    ASSERT_TRUE(r.pose.matrix().allFinite()) << k;
    ASSERT_TRUE(r.covariance.allFinite()) << k;
    EXPECT_GE(r.ess, 1.0 - 1e-9);
    EXPECT_TRUE(std::isfinite(r.log_likelihood));
  }
  EXPECT_LT(position_error(run.results.back().pose, run.truth.back()), 0.05);
}

namespace {
// A model that cannot explain anything: every pose scores −∞.
class ImpossibleModel final : public cl::ObservationModel {
 public:
  std::string name() const override { return "impossible"; }
  void prepare(const Scan&, const Eigen::AlignedBox3d&) override {}
  std::size_t term_count() const override { return 1; }
  void set_pose_blur(double) override {}
  cl::ObservationScore score(const cl::Pose3&, Scratch*) const override {
    return {-std::numeric_limits<double>::infinity(), 0.0};
  }
};
}  // namespace

TEST(StiffCases, AllParticlesAtMinusInfinity) {
  const auto map = ct::make_box_room();
  cl::FreeSpace free_space(map);
  cl::MotionModel motion(cl::MotionModelConfig{}, free_space);
  cl::ParticleFilter filter(cl::ParticleFilterConfig{}, motion, free_space);
  std::mt19937_64 rng(1);
  filter.initialise_global(200, rng);
  ImpossibleModel model;
  std::vector<std::unique_ptr<cl::ObservationModel::Scratch>> scratches(2);
  const cl::WeightSummary summary = filter.weight(model, scratches);
  EXPECT_TRUE(summary.all_minus_infinity);
  EXPECT_NEAR(summary.ess, 200.0, 1e-6);
  for (const auto& p : filter.particles()) EXPECT_NEAR(p.log_weight, -std::log(200.0), 1e-12);
  EXPECT_FALSE(filter.resample_if_needed(rng));  // uniform: nothing to resample
  filter.inject_global(0.5, rng);
  EXPECT_EQ(filter.particles().size(), 200u);
  for (const auto& p : filter.particles()) EXPECT_GE(p.cell, 0);
}

TEST(StiffCases, PoseOutsideTheBuildingRecoversGlobally) {
  // Initialised 5 m outside the room: nothing fits, the filter declares itself lost, injects
  // global particles (reported), and finds the sensor.
  const auto map = ct::make_box_room();
  auto config = small_config("conic-beam");
  config.filter.max_particles = 3000;
  config.observation.conic_beam.beams.max_beams = 500;
  cl::Localizer localizer(map, vlp16(), config);
  cl::Vector6 sigma;
  sigma << 0.2, 0.2, 0.01, 0.005, 0.005, 0.1;
  localizer.initialise(cl::make_pose(-5.0, 3.0, 1.2, 0.0), sigma);
  const PathRun run = run_path(map, localizer, 60, 0.02);
  int recoveries = 0;
  for (const auto& r : run.results) recoveries += r.recovered ? 1 : 0;
  EXPECT_GE(recoveries, 1);
  EXPECT_FALSE(run.results.front().recovered && run.results.size() < 2);
  EXPECT_LT(position_error(run.results.back().pose, run.truth.back()), 0.1);
  EXPECT_LT(yaw_error_deg(run.results.back().pose, run.truth.back()), 2.0);
}

TEST(StiffCases, EmptyScanLeavesTheFilterUntouched) {
  const auto map = ct::make_box_room();
  for (const std::string model : {"conic-beam", "conic-segment", "point-to-plane"}) {
    cl::Localizer localizer(map, vlp16(), small_config(model));
    cl::Vector6 sigma;
    sigma << 0.05, 0.05, 0.01, 0.005, 0.005, 0.02;
    localizer.initialise(path_pose(0), sigma);
    const std::size_t before = localizer.particles().size();
    Scan empty;  // no rings at all
    empty.end_time_s = 0.1;
    const auto r1 = localizer.update(empty);
    std::mt19937_64 scan_rng(1);
    Scan no_returns = ct::make_scan(map, path_pose(0), ct::SyntheticScanOptions{}, scan_rng);
    for (auto& ring : no_returns.rings) {
      for (auto& ret : ring.returns) ret.status = conicloc::sensor::ReturnStatus::NoReturn;
    }
    no_returns.end_time_s = 0.2;
    const auto r2 = localizer.update(no_returns);
    for (const auto& r : {r1, r2}) {
      EXPECT_EQ(r.terms, 0u) << model;
      EXPECT_FALSE(r.recovered);
      EXPECT_FALSE(r.resampled);
      EXPECT_EQ(r.particles, before);
      EXPECT_TRUE(r.pose.matrix().allFinite());
      EXPECT_LT(position_error(r.pose, path_pose(0)), 0.05) << model;
    }
  }
}

TEST(StiffCases, ScanWithOnlyClutter) {
  // Tracking well, then one scan of nothing but clutter (a box of 0.8 m around the sensor that the
  // map lacks): finite scores, no recovery from one bad scan, the estimate does not jump, and
  // tracking continues.
  const auto map = ct::make_box_room();
  cl::Localizer localizer(map, vlp16(), small_config("conic-beam"));
  cl::Vector6 sigma;
  sigma << 0.05, 0.05, 0.01, 0.005, 0.005, 0.02;
  localizer.initialise(path_pose(0), sigma);
  std::mt19937_64 rng(3);
  ct::SyntheticScanOptions options;
  options.range_sigma_m = 0.01;
  for (int k = 0; k < 10; ++k) {
    options.start_time_s = 0.1 * k;
    localizer.update(ct::make_scan(map, path_pose(k), path_pose(k + 1), options, rng));
  }
  options.start_time_s = 1.0;
  Scan clutter = ct::make_scan(map, path_pose(10), path_pose(11), options, rng);
  for (auto& ring : clutter.rings) {
    for (auto& ret : ring.returns) {
      ret.status = conicloc::sensor::ReturnStatus::Valid;
      ret.range_m = 0.8 + 0.05 * std::sin(7.0 * ret.azimuth_rad);
    }
  }
  const auto r = localizer.update(clutter);
  EXPECT_TRUE(std::isfinite(r.log_likelihood));
  EXPECT_LT(r.inlier_fraction, 0.1);
  EXPECT_FALSE(r.recovered);
  EXPECT_LT(position_error(r.pose, path_pose(11)), 0.1);
  for (int k = 11; k < 20; ++k) {
    options.start_time_s = 0.1 * k;
    const auto next =
        localizer.update(ct::make_scan(map, path_pose(k), path_pose(k + 1), options, rng));
    EXPECT_LT(position_error(next.pose, path_pose(k + 1)), 0.05) << k;
  }
}
