#include "eval/trajectory_metrics.hpp"

#include <algorithm>
#include <cmath>

#include "localizer/conic/pose.hpp"
#include "localizer/filter/median.hpp"

namespace conicloc::eval {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

struct MatchedPair {
  double time_s;
  Eigen::Isometry3d truth;
  Eigen::Isometry3d estimate;
};

// Relative pose error over `delta_m` of travelled truth path (evo: RPE with delta unit metres):
// E_ij = (T_truth_i⁻¹ T_truth_j)⁻¹ (T_est_i⁻¹ T_est_j), normalised by the path length i → j.
void relative_errors(const std::vector<MatchedPair>& pairs, double delta_m,
                     std::vector<double>& trans_per_m, std::vector<double>& rot_deg_per_m) {
  std::vector<double> path_m(pairs.size(), 0.0);
  for (std::size_t i = 1; i < pairs.size(); ++i) {
    path_m[i] =
        path_m[i - 1] + (pairs[i].truth.translation() - pairs[i - 1].truth.translation()).norm();
  }
  std::size_t j = 0;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    j = std::max(j, i + 1);
    while (j < pairs.size() && path_m[j] - path_m[i] < delta_m) ++j;
    if (j >= pairs.size()) break;
    const double length_m = path_m[j] - path_m[i];
    const Eigen::Isometry3d truth_ij = pairs[i].truth.inverse() * pairs[j].truth;
    const Eigen::Isometry3d est_ij = pairs[i].estimate.inverse() * pairs[j].estimate;
    const Eigen::Isometry3d error = truth_ij.inverse() * est_ij;
    trans_per_m.push_back(error.translation().norm() / length_m);
    rot_deg_per_m.push_back(Eigen::AngleAxisd(error.linear()).angle() * kRadToDeg / length_m);
  }
}

}  // namespace

ErrorStats summarize(std::vector<double> errors) {
  ErrorStats stats;
  stats.count = errors.size();
  if (errors.empty()) return stats;
  double sum = 0.0, sum_sq = 0.0;
  for (double e : errors) {
    sum += e;
    sum_sq += e * e;
    stats.max = std::max(stats.max, e);
  }
  const auto n = static_cast<double>(errors.size());
  stats.mean = sum / n;
  stats.rmse = std::sqrt(sum_sq / n);
  stats.median = localizer::median_of(errors);
  return stats;
}

std::optional<Eigen::Isometry3d> interpolate_pose(const std::vector<io::StampedPose>& truth,
                                                  double time_s, double max_gap_s) {
  if (truth.empty()) return std::nullopt;
  const auto after =
      std::lower_bound(truth.begin(), truth.end(), time_s,
                       [](const io::StampedPose& pose, double t) { return pose.time_s < t; });
  if (after != truth.end() && after->time_s == time_s) return after->pose;
  if (after == truth.begin() || after == truth.end()) {
    // Outside the truth: accept only an estimate within max_gap_s of the nearest end.
    const auto& end = after == truth.begin() ? truth.front() : truth.back();
    if (std::abs(end.time_s - time_s) <= max_gap_s) return end.pose;
    return std::nullopt;
  }
  const auto before = std::prev(after);
  if (after->time_s - before->time_s > 2.0 * max_gap_s) return std::nullopt;
  const double s = (time_s - before->time_s) / (after->time_s - before->time_s);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = (1.0 - s) * before->pose.translation() + s * after->pose.translation();
  const Eigen::Quaterniond q0(before->pose.linear()), q1(after->pose.linear());
  pose.linear() = q0.slerp(s, q1).toRotationMatrix();
  return pose;
}

std::optional<double> time_to_settle_s(const std::vector<PoseError>& errors, double xy_m) {
  std::optional<double> settled;
  for (auto it = errors.rbegin(); it != errors.rend() && it->xy_m <= xy_m; ++it)
    settled = it->time_s;
  if (!settled) return std::nullopt;
  return *settled - errors.front().time_s;
}

TrajectoryMetrics evaluate_trajectory(const std::vector<io::StampedPose>& truth,
                                      const std::vector<io::StampedPose>& estimate,
                                      const MetricsConfig& config) {
  TrajectoryMetrics metrics;
  metrics.estimates = estimate.size();
  std::vector<MatchedPair> pairs;
  for (const auto& est : estimate) {
    const auto truth_pose = interpolate_pose(truth, est.time_s, config.max_time_gap_s);
    if (!truth_pose) {
      ++metrics.missing;
      continue;
    }
    pairs.push_back({est.time_s, *truth_pose, est.pose});
  }
  metrics.matched = pairs.size();

  std::vector<double> xy, z, heading;
  for (const auto& pair : pairs) {
    const Eigen::Vector3d d = pair.estimate.translation() - pair.truth.translation();
    PoseError error;
    error.time_s = pair.time_s;
    error.xy_m = d.head<2>().norm();
    error.z_m = std::abs(d.z());
    error.heading_deg = std::abs(localizer::angle_difference(localizer::yaw_of(pair.estimate),
                                                             localizer::yaw_of(pair.truth))) *
                        kRadToDeg;
    metrics.errors.push_back(error);
    xy.push_back(error.xy_m);
    z.push_back(error.z_m);
    heading.push_back(error.heading_deg);
  }
  metrics.ate_xy_m = summarize(xy);
  metrics.ate_z_m = summarize(z);
  metrics.heading_deg = summarize(heading);

  std::vector<double> rpe_trans, rpe_rot;
  relative_errors(pairs, config.rpe_delta_m, rpe_trans, rpe_rot);
  metrics.rpe_trans_per_m = summarize(rpe_trans);
  metrics.rpe_rot_deg_per_m = summarize(rpe_rot);

  // Converged at the first error after which all errors stay within the thresholds.
  if (!metrics.errors.empty() && !estimate.empty()) {
    std::optional<double> settled;
    for (auto it = metrics.errors.rbegin(); it != metrics.errors.rend(); ++it) {
      if (it->xy_m > config.converged_xy_m || it->heading_deg > config.converged_heading_deg) break;
      settled = it->time_s;
    }
    if (settled) metrics.convergence_time_s = *settled - estimate.front().time_s;
  }
  return metrics;
}

}  // namespace conicloc::eval
