// The estimate's twins on the other storeys (storey_twins.hpp): where they stand, how the scans'
// evidence moves their odds, and a localizer that does not call a storey the scans cannot tell.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "localizer/filter/localizer.hpp"
#include "localizer/filter/storey_twins.hpp"
#include "synthetic_room.hpp"

namespace cl = conicloc::localizer;
namespace ct = conicloc::test;

namespace {

constexpr double kStorey_m = 3.437;
constexpr double kMounting_m = 1.2;

cl::PoseState upstairs_pose() {
  cl::PoseState pose;
  pose.x = 3.0;
  pose.y = 2.5;
  pose.z = kStorey_m + kMounting_m;
  pose.roll = 0.01;
  pose.pitch = -0.02;
  pose.yaw = 0.4;
  return pose;
}

/// Scores for StoreyTwins::update: the estimate (first pose) `estimate`, every twin `twin`.
cl::StoreyTwins::ScorePoses scores(double estimate, double twin) {
  return [=](const std::vector<cl::PoseState>& poses) {
    std::vector<double> log_likelihoods(poses.size(), twin);
    log_likelihoods.front() = estimate;
    return log_likelihoods;
  };
}

/// The box room under a room half its length (x from 0 to 5 m) one storey up, with a pillar in
/// a corner: without it the upper room looks the same from (x, y, ψ) and from its half turn
/// (5 − x, 6 − y, ψ + π), tilt and all, and no scan can tell the two.
conicloc::maps::PlaneMap room_under_a_smaller_one() {
  conicloc::maps::PlaneMap map = ct::make_box_room();
  ct::add_room_storey(map, kStorey_m, {5, 6}, false);
  ct::add_box(map, 1, {0.8, 4.5, kStorey_m}, {1.3, 5.0, kStorey_m + 3.0}, false);
  return map;
}

}  // namespace

TEST(StoreyTwins, ATwinStandsAsHighAboveItsStoreysFloorAtTheSamePlace) {
  const auto map = ct::make_identical_storeys(kStorey_m);
  const cl::FreeSpace free_space(map);
  const cl::StoreyTwins twins(map, free_space, {});
  const cl::PoseState estimate = upstairs_pose();
  const auto below = twins.twin_pose(estimate, kMounting_m, -1);
  ASSERT_TRUE(below.has_value());
  EXPECT_NEAR(below->z, kMounting_m, 1e-12);
  EXPECT_EQ(below->x, estimate.x);
  EXPECT_EQ(below->y, estimate.y);
  EXPECT_EQ(below->roll, estimate.roll);
  EXPECT_EQ(below->pitch, estimate.pitch);
  EXPECT_EQ(below->yaw, estimate.yaw);
  // A sensor held higher on the stair or a box keeps that height on the other storey.
  cl::PoseState higher = estimate;
  higher.z += 0.3;
  EXPECT_NEAR(twins.twin_pose(higher, kMounting_m, -1)->z, kMounting_m + 0.3, 1e-12);
  EXPECT_FALSE(twins.twin_pose(estimate, kMounting_m, 1).has_value());  // no storey above
  cl::PoseState outside = estimate;
  outside.x = 20.0;  // over no navigable cell
  EXPECT_FALSE(twins.twin_pose(outside, kMounting_m, -1).has_value());
}

TEST(StoreyTwins, ScansThatScoreTheSameOnBothStoreysKeepEvenOdds) {
  const auto map = ct::make_identical_storeys(kStorey_m);
  const cl::FreeSpace free_space(map);
  cl::StoreyTwins twins(map, free_space, {});
  twins.start(upstairs_pose(), kMounting_m);
  // The storey above the upper one does not exist: one twin, a storey down, at even odds.
  const auto started = twins.current(upstairs_pose(), kMounting_m);
  EXPECT_NEAR(started.estimate_share, 0.5, 1e-12);
  EXPECT_NEAR(started.z_variance_m2, kStorey_m * kStorey_m / 4.0, 1e-9);
  cl::StoreyTwinsUpdate update;
  for (int scan = 0; scan < 20; ++scan)
    update = twins.update(upstairs_pose(), kMounting_m, 0.01, scores(2000.0, 2000.0));
  ASSERT_EQ(twins.twins().size(), 1U);
  EXPECT_EQ(twins.twins().front().offset, -1);
  EXPECT_NEAR(update.estimate_share, 0.5, 1e-12);
  EXPECT_NEAR(update.z_variance_m2, kStorey_m * kStorey_m / 4.0, 1e-9);
  EXPECT_FALSE(update.move_z_m.has_value());
}

TEST(StoreyTwins, ATwinTheScansFavourTakesTheCloud) {
  const auto map = ct::make_identical_storeys(kStorey_m);
  const cl::FreeSpace free_space(map);
  cl::StoreyTwins twins(map, free_space, {});  // switch_share 0.8: log-odds ln 4 = 1.39
  twins.start(upstairs_pose(), kMounting_m);
  // 100 nats a scan at τ = 0.01: one nat of odds a scan.
  const auto first = twins.update(upstairs_pose(), kMounting_m, 0.01, scores(1900.0, 2000.0));
  EXPECT_NEAR(first.estimate_share, 1.0 / (1.0 + std::exp(1.0)), 1e-12);
  EXPECT_FALSE(first.move_z_m.has_value());
  const auto second = twins.update(upstairs_pose(), kMounting_m, 0.01, scores(1900.0, 2000.0));
  ASSERT_TRUE(second.move_z_m.has_value());
  EXPECT_NEAR(*second.move_z_m, -kStorey_m, 1e-12);
  // Counted from the storey below now: the upper one is its twin, two nats behind.
  ASSERT_EQ(twins.twins().size(), 1U);
  EXPECT_EQ(twins.twins().front().offset, 1);
  EXPECT_NEAR(twins.twins().front().log_odds, -2.0, 1e-12);
  EXPECT_NEAR(second.estimate_share, 1.0 / (1.0 + std::exp(-2.0)), 1e-12);
}

TEST(StoreyTwins, TakingTheCloudCountsEveryTwinFromTheNewStorey) {
  const auto map = ct::make_identical_storeys(kStorey_m, 3);
  const cl::FreeSpace free_space(map);
  cl::StoreyTwins twins(map, free_space, {});
  cl::PoseState ground = upstairs_pose();
  ground.z = kMounting_m;  // storey 0: twins one and two storeys up
  twins.start(ground, kMounting_m);
  // The top storey scores 300 nats over the estimate and the middle one 100 (τ = 0.01).
  const auto score = [](const std::vector<cl::PoseState>& poses) {
    std::vector<double> log_likelihoods;
    for (const cl::PoseState& pose : poses)
      log_likelihoods.push_back(pose.z > 2.0 * kStorey_m ? 2300.0
                                : pose.z > kStorey_m     ? 2100.0
                                                         : 2000.0);
    return log_likelihoods;
  };
  const auto update = twins.update(ground, kMounting_m, 0.01, score);
  ASSERT_TRUE(update.move_z_m.has_value());
  EXPECT_NEAR(*update.move_z_m, 2.0 * kStorey_m, 1e-12);
  // From the top storey: the ground floor two down at −3 nats, the middle one down at −2.
  ASSERT_EQ(twins.twins().size(), 2U);
  for (const cl::StoreyTwin& twin : twins.twins()) {
    if (twin.offset == -2) {
      EXPECT_NEAR(twin.log_odds, -3.0, 1e-12);
    } else {
      EXPECT_EQ(twin.offset, -1);
      EXPECT_NEAR(twin.log_odds, -2.0, 1e-12);
    }
  }
  EXPECT_NEAR(update.estimate_share, 1.0 / (1.0 + std::exp(-3.0) + std::exp(-2.0)), 1e-12);
}

// The estimate climbs a storey (a stair) with its twins one and two storeys up: the upper twin's
// storey no longer exists. It is dropped that scan, before anything is scored, and the twin that
// is left is scored at its own storey.
TEST(StoreyTwins, ATwinWhoseStoreyTheEstimateClimbsPastIsDroppedUnscored) {
  const auto map = ct::make_identical_storeys(kStorey_m, 3);
  const cl::FreeSpace free_space(map);
  cl::StoreyTwins twins(map, free_space, {});
  cl::PoseState estimate = upstairs_pose();
  estimate.z = kMounting_m;
  twins.start(estimate, kMounting_m);
  ASSERT_EQ(twins.twins().size(), 2U);
  estimate.z = kStorey_m + kMounting_m;  // up the stair: the twins stand at +1 and +2 from here
  std::vector<double> scored_z;
  const auto score = [&](const std::vector<cl::PoseState>& poses) {
    for (const cl::PoseState& pose : poses) scored_z.push_back(pose.z);
    return std::vector<double>(poses.size(), 2000.0);
  };
  twins.update(estimate, kMounting_m, 0.01, score);
  ASSERT_EQ(twins.twins().size(), 1U);
  EXPECT_EQ(twins.twins().front().offset, 1);  // the top storey, one up from here
  ASSERT_EQ(scored_z.size(), 2U);              // the estimate and one twin
  EXPECT_NEAR(scored_z[1], 2.0 * kStorey_m + kMounting_m, 1e-9);
}

TEST(StoreyTwins, OverwhelmingEvidenceMovesTheCloudAndNothingTurnsNaN) {
  const auto map = ct::make_identical_storeys(kStorey_m);
  const cl::FreeSpace free_space(map);
  cl::StoreyTwins twins(map, free_space, {});
  twins.start(upstairs_pose(), kMounting_m);
  const auto update = twins.update(upstairs_pose(), kMounting_m, 1.0, scores(1000.0, 1800.0));
  ASSERT_TRUE(update.move_z_m.has_value());  // 800 nats: e^{−800} underflows, the share does not
  EXPECT_NEAR(*update.move_z_m, -kStorey_m, 1e-12);
  EXPECT_EQ(update.estimate_share, 1.0);
  EXPECT_EQ(update.z_variance_m2, 0.0);
  EXPECT_TRUE(twins.empty());  // the storey it left, 800 nats behind, at once
  // No evidence, a twin explaining nothing: 0 · (−∞) is no number, and carries none.
  twins.start(upstairs_pose(), kMounting_m);
  const auto none = twins.update(upstairs_pose(), kMounting_m, 0.0,
                                 scores(1000.0, -std::numeric_limits<double>::infinity()));
  EXPECT_EQ(twins.twins().size(), 1U);
  EXPECT_NEAR(none.estimate_share, 0.5, 1e-12);
  // Evidence: the twin that explains nothing is gone.
  twins.update(upstairs_pose(), kMounting_m, 0.01,
               scores(1000.0, -std::numeric_limits<double>::infinity()));
  EXPECT_TRUE(twins.empty());
}

TEST(StoreyTwins, ATwinTheScansRefuteIsDropped) {
  const auto map = ct::make_identical_storeys(kStorey_m);
  const cl::FreeSpace free_space(map);
  cl::StoreyTwins twins(map, free_space, {});  // min_share 1e-4: log-odds −9.2
  twins.start(upstairs_pose(), kMounting_m);
  const auto first = twins.update(upstairs_pose(), kMounting_m, 0.01, scores(2000.0, 1100.0));
  EXPECT_EQ(twins.twins().size(), 1U);  // −9 nats: share 1.2e-4, kept
  EXPECT_GT(first.z_variance_m2, 0.0);
  const auto second = twins.update(upstairs_pose(), kMounting_m, 0.01, scores(2000.0, 1970.0));
  EXPECT_TRUE(twins.empty());  // −9.3 nats: share 0.9e-4, dropped
  EXPECT_EQ(second.estimate_share, 1.0);
  EXPECT_EQ(second.z_variance_m2, 0.0);
}

TEST(StoreyTwins, ATwinWithoutItsStoreysFloorUnderItIsDropped) {
  const auto map = room_under_a_smaller_one();
  const cl::FreeSpace free_space(map);
  cl::StoreyTwinsConfig config;
  config.max_missing_scans = 3;
  cl::StoreyTwins twins(map, free_space, config);
  cl::PoseState estimate = upstairs_pose();
  estimate.z = kMounting_m;
  twins.start(estimate, kMounting_m);
  ASSERT_TRUE(twins.twin_pose(estimate, kMounting_m, 1).has_value());
  estimate.x = 8.0;  // downstairs, beyond the upper room
  ASSERT_FALSE(twins.twin_pose(estimate, kMounting_m, 1).has_value());
  for (int scan = 0; scan <= config.max_missing_scans; ++scan) {
    ASSERT_FALSE(twins.empty()) << scan;
    twins.update(estimate, kMounting_m, 0.01, scores(2000.0, 2000.0));
  }
  EXPECT_TRUE(twins.empty());
}

TEST(StoreyTwins, AnEstimateOffEveryCellLeavesTheOddsAsTheyWere) {
  const auto map = ct::make_identical_storeys(kStorey_m);
  const cl::FreeSpace free_space(map);
  cl::StoreyTwins twins(map, free_space, {});
  twins.start(upstairs_pose(), kMounting_m);
  twins.update(upstairs_pose(), kMounting_m, 0.01, scores(1950.0, 2000.0));
  cl::PoseState outside = upstairs_pose();
  outside.x = 20.0;
  cl::StoreyTwinsUpdate update;
  for (int scan = 0; scan < 20; ++scan)
    update = twins.update(outside, kMounting_m, 0.01, scores(2000.0, 0.0));
  ASSERT_EQ(twins.twins().size(), 1U);
  EXPECT_NEAR(twins.twins().front().log_odds, 0.5, 1e-12);
  // ... and what it reports still doubts the storey, with the heights of the last one it stood on.
  const double share = 1.0 / (1.0 + std::exp(0.5));
  EXPECT_NEAR(update.estimate_share, share, 1e-12);
  EXPECT_NEAR(update.z_variance_m2, share * (1.0 - share) * kStorey_m * kStorey_m, 1e-9);
  EXPECT_NEAR(twins.current(outside, kMounting_m).estimate_share, share, 1e-12);
}

namespace {

cl::LocalizerConfig global_config() {
  cl::LocalizerConfig config;
  config.observation.model = "conic-beam";
  config.observation.conic_beam.beams.max_beams = 500;
  config.filter.min_particles = 150;
  config.filter.max_particles = 3000;
  config.motion.height_above_floor_m = kMounting_m;
  config.threads = 2;
  config.seed = 3;
  return config;
}

/// `scans` updates of a global start in `map`, the sensor standing still at `truth`.
std::vector<cl::UpdateResult> stand_still(const conicloc::maps::PlaneMap& map,
                                          const cl::Pose3& truth, int scans) {
  cl::Localizer localizer(map, ct::vlp16(), global_config());
  localizer.initialise_global();
  std::mt19937_64 rng(4);
  ct::SyntheticScanOptions options;
  options.range_sigma_m = 0.01;
  std::vector<cl::UpdateResult> results;
  for (int scan = 0; scan < scans; ++scan) {
    options.start_time_s = 0.1 * scan;
    results.push_back(localizer.update(ct::make_scan(map, truth, truth, options, rng)));
  }
  return results;
}

}  // namespace

// A global start over two identical storeys, the sensor standing still upstairs: nothing the
// scans hold tells the storeys apart, and the localizer must not say `tracking` on either.
// Without the twins the cloud settles on one storey and is tracked as certain.
TEST(StoreyTwins, ALocalizerDoesNotCallAStoreyTheScansCannotTell) {
  const auto map = ct::make_identical_storeys(kStorey_m);
  const cl::Pose3 truth = upstairs_pose().to_pose();
  const auto results = stand_still(map, truth, 40);
  for (std::size_t scan = 0; scan < results.size(); ++scan)
    EXPECT_NE(results[scan].status, cl::LocalizerStatus::Tracking) << "scan " << scan;
  // Settled in x, y on the place; between the storeys, even odds: var z of the two.
  const cl::UpdateResult& last = results.back();
  EXPECT_LT((last.pose.translation() - truth.translation()).head<2>().norm(), 0.05);
  EXPECT_GT(last.covariance(2, 2), 0.9 * kStorey_m * kStorey_m / 4.0);
  EXPECT_LT(last.mode_weight, 0.6);
  EXPECT_EQ(last.storey_twins, 1U);
  EXPECT_NEAR(last.storey_share, 0.5, 0.01);
}

// Storeys that differ where the sensor looks: the twin below is refuted within a few scans of
// the cloud settling, and the localizer tracks the storey it stands on.
TEST(StoreyTwins, ALocalizerTracksAStoreyTheScansTellApart) {
  const auto map = room_under_a_smaller_one();
  const cl::Pose3 truth = upstairs_pose().to_pose();
  const auto results = stand_still(map, truth, 40);
  const cl::UpdateResult& last = results.back();
  EXPECT_EQ(last.status, cl::LocalizerStatus::Tracking);
  EXPECT_LT((last.pose.translation() - truth.translation()).norm(), 0.05);
  EXPECT_LT(last.covariance(2, 2), 0.01);
  EXPECT_EQ(last.storey_twins, 0U);
  EXPECT_EQ(last.storey_share, 1.0);
}
