#include <gtest/gtest.h>

#include <cmath>

#include "eval/trajectory_metrics.hpp"
#include "localizer/conic/pose.hpp"

namespace ce = conicloc::eval;
using conicloc::io::StampedPose;
using conicloc::localizer::make_pose;

namespace {

constexpr double kDeg = M_PI / 180.0;

// Straight line along x at 1 m/s, one pose every 0.1 s, heading +x.
std::vector<StampedPose> straight_truth(double duration_s) {
  std::vector<StampedPose> poses;
  for (int i = 0; i * 0.1 <= duration_s + 1e-9; ++i) {
    const double t = i * 0.1;
    poses.push_back({t, make_pose(t, 0.0, 1.0, 0.0)});
  }
  return poses;
}

}  // namespace

TEST(TrajectoryMetrics, SummarizeHandComputed) {
  const auto stats = ce::summarize({3.0, 4.0, 0.0, 1.0});
  EXPECT_DOUBLE_EQ(stats.mean, 2.0);
  EXPECT_DOUBLE_EQ(stats.rmse, std::sqrt((9.0 + 16.0 + 0.0 + 1.0) / 4.0));
  EXPECT_DOUBLE_EQ(stats.median, 2.0);  // even count: mean of 1 and 3
  EXPECT_DOUBLE_EQ(stats.max, 4.0);
  EXPECT_EQ(ce::summarize({}).count, 0u);
  EXPECT_DOUBLE_EQ(ce::summarize({5.0, 1.0, 2.0}).median, 2.0);
}

TEST(TrajectoryMetrics, ConstantOffsetAndHeading) {
  const auto truth = straight_truth(5.0);
  std::vector<StampedPose> estimate;
  for (const auto& pose : truth) {
    // 3 cm east, 4 cm north (5 cm in xy), 2 cm up, 2° heading error.
    estimate.push_back({pose.time_s, make_pose(pose.time_s + 0.03, 0.04, 1.02, 2.0 * kDeg)});
  }
  const auto m = ce::evaluate_trajectory(truth, estimate);
  EXPECT_EQ(m.matched, truth.size());
  EXPECT_EQ(m.missing, 0u);
  EXPECT_NEAR(m.ate_xy_m.rmse, 0.05, 1e-12);
  EXPECT_NEAR(m.ate_xy_m.max, 0.05, 1e-12);
  EXPECT_NEAR(m.ate_z_m.mean, 0.02, 1e-12);
  EXPECT_NEAR(m.heading_deg.rmse, 2.0, 1e-9);
  // A constant heading offset turns the 1 m step of the estimate by 2°: the relative translation
  // error of a 1 m step is |R(2°)·(1,0,0) − (1,0,0)| = 2 sin(1°), and 2° of rotation error.
  EXPECT_NEAR(m.rpe_trans_per_m.mean, 2.0 * std::sin(1.0 * kDeg), 1e-6);
  EXPECT_NEAR(m.rpe_rot_deg_per_m.mean, 0.0, 1e-9);
  ASSERT_TRUE(m.convergence_time_s.has_value());
  EXPECT_DOUBLE_EQ(*m.convergence_time_s, 0.0);
}

TEST(TrajectoryMetrics, TimestampsBetweenTruthAreInterpolated) {
  const auto truth = straight_truth(2.0);
  // Estimates exactly on the truth path but at times between truth samples.
  std::vector<StampedPose> estimate;
  for (double t = 0.05; t < 2.0; t += 0.1) estimate.push_back({t, make_pose(t, 0.0, 1.0, 0.0)});
  const auto m = ce::evaluate_trajectory(truth, estimate);
  EXPECT_EQ(m.matched, estimate.size());
  EXPECT_NEAR(m.ate_xy_m.max, 0.0, 1e-12);
}

TEST(TrajectoryMetrics, InterpolationSlerpsRotation) {
  const std::vector<StampedPose> truth = {{0.0, make_pose(0, 0, 0, 0.0)},
                                          {1.0, make_pose(2, 0, 0, 90.0 * kDeg)}};
  const auto mid = ce::interpolate_pose(truth, 0.5, 1.0);
  ASSERT_TRUE(mid.has_value());
  EXPECT_NEAR(mid->translation().x(), 1.0, 1e-12);
  EXPECT_NEAR(conicloc::localizer::yaw_of(*mid), 45.0 * kDeg, 1e-12);
  EXPECT_FALSE(ce::interpolate_pose(truth, 0.5, 0.1).has_value());  // gap of 1 s > 2 × 0.1 s
  EXPECT_FALSE(ce::interpolate_pose(truth, 3.0, 1.0).has_value());  // beyond the truth
  EXPECT_TRUE(ce::interpolate_pose(truth, 1.05, 0.1).has_value());  // just past the end
}

TEST(TrajectoryMetrics, MissingPosesAreCounted) {
  auto truth = straight_truth(4.0);
  // Truth has a 2 s hole between t = 1 and t = 3.
  truth.erase(
      std::remove_if(truth.begin(), truth.end(),
                     [](const StampedPose& p) { return p.time_s > 1.05 && p.time_s < 2.95; }),
      truth.end());
  std::vector<StampedPose> estimate;
  for (double t = 0.0; t <= 4.0 + 1e-9; t += 0.5) estimate.push_back({t, make_pose(t, 0, 1, 0)});
  estimate.push_back({10.0, make_pose(10, 0, 1, 0)});  // long after the truth ends
  const auto m = ce::evaluate_trajectory(truth, estimate);
  EXPECT_EQ(m.estimates, 10u);
  EXPECT_EQ(m.missing, 4u);  // t = 1.5, 2.0, 2.5 in the hole and t = 10
  EXPECT_EQ(m.matched, 6u);
}

TEST(TrajectoryMetrics, ConvergenceAfterGlobalStart) {
  const auto truth = straight_truth(5.0);
  std::vector<StampedPose> estimate;
  for (const auto& pose : truth) {
    // Wrong by 3 m until t = 2 s (a global start), then within 5 cm.
    const double error_m = pose.time_s < 2.0 - 1e-9 ? 3.0 : 0.05;
    estimate.push_back({pose.time_s, make_pose(pose.time_s + error_m, 0, 1, 0)});
  }
  const auto m = ce::evaluate_trajectory(truth, estimate);
  ASSERT_TRUE(m.convergence_time_s.has_value());
  EXPECT_NEAR(*m.convergence_time_s, 2.0, 1e-9);

  estimate.back().pose = make_pose(10, 10, 1, 0);  // diverges at the end: never settled
  EXPECT_FALSE(ce::evaluate_trajectory(truth, estimate).convergence_time_s.has_value());
}

TEST(TrajectoryMetrics, TimeToSettleIsFromTheFirstErrorUntilTheErrorStaysBelow) {
  const auto errors = [](const std::vector<std::pair<double, double>>& time_xy) {
    std::vector<ce::PoseError> list;
    for (const auto& [t, xy] : time_xy) list.push_back({.time_s = t, .xy_m = xy});
    return list;
  };
  // 0.08 at 11 s does not count: the error rises above 0.10 again at 12 s.
  EXPECT_NEAR(*ce::time_to_settle_s(
                  errors({{10, 3.0}, {11, 0.08}, {12, 0.3}, {13, 0.10}, {14, 0.02}}), 0.10),
              3.0, 1e-12);
  EXPECT_NEAR(*ce::time_to_settle_s(errors({{5, 0.01}, {6, 0.02}}), 0.10), 0.0, 1e-12);
  EXPECT_FALSE(ce::time_to_settle_s(errors({{5, 0.01}, {6, 0.2}}), 0.10));
  EXPECT_FALSE(ce::time_to_settle_s({}, 0.10));
}
