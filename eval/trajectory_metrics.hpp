#pragma once
// Pose accuracy of an estimated trajectory against ground truth, with evo's conventions for TUM
// files and no alignment (the map frame is fixed, so any offset is an error).

#include <optional>
#include <vector>

#include "io/tum_trajectory.hpp"

namespace conicloc::eval {

struct ErrorStats {
  double rmse = 0.0;
  double mean = 0.0;
  double median = 0.0;
  double max = 0.0;
  std::size_t count = 0;
};

/// Summary statistics of non-negative errors; all zero (count 0) for an empty list.
ErrorStats summarize(std::vector<double> errors);

struct MetricsConfig {
  /// An estimate is matched to the truth interpolated at its time; it counts as missing when no
  /// truth pose lies within this many seconds on both sides (or beyond the truth's ends).
  double max_time_gap_s = 0.2;
  double rpe_delta_m = 1.0;  ///< relative pose error over this much travelled truth path
  /// Converged from the first estimate after which every error stays below both thresholds.
  double converged_xy_m = 0.2;
  double converged_heading_deg = 5.0;
};

/// One matched estimate.
struct PoseError {
  double time_s = 0.0;
  double xy_m = 0.0;         ///< horizontal position error
  double z_m = 0.0;          ///< |Δz|
  double heading_deg = 0.0;  ///< |Δyaw|, degrees
};

struct TrajectoryMetrics {
  ErrorStats ate_xy_m;  ///< absolute position error in the horizontal plane
  ErrorStats ate_z_m;
  ErrorStats heading_deg;
  ErrorStats rpe_trans_per_m;  ///< relative translation error per metre travelled (m/m)
  ErrorStats rpe_rot_deg_per_m;
  std::size_t estimates = 0;
  std::size_t matched = 0;
  std::size_t missing = 0;  ///< estimates without truth around them
  /// Time from the first estimate until the errors stay below the convergence thresholds;
  /// empty when the trajectory never settles.
  std::optional<double> convergence_time_s;
  std::vector<PoseError> errors;  ///< per matched estimate, in time order
};

/// Truth pose at `time_s`: linear in translation, slerp in rotation, between the bracketing truth
/// poses; empty when `time_s` lies outside the truth or in a gap wider than `max_gap_s`.
std::optional<Eigen::Isometry3d> interpolate_pose(const std::vector<io::StampedPose>& truth,
                                                  double time_s, double max_gap_s);

/// Seconds from the first matched estimate until the horizontal error stays at or below `xy_m`
/// to the end (the time a global start takes to converge, or a kidnapped filter to recover, to
/// that accuracy); empty when the last error is above it or nothing was matched.
std::optional<double> time_to_settle_s(const std::vector<PoseError>& errors, double xy_m);

TrajectoryMetrics evaluate_trajectory(const std::vector<io::StampedPose>& truth,
                                      const std::vector<io::StampedPose>& estimate,
                                      const MetricsConfig& config = {});

}  // namespace conicloc::eval
