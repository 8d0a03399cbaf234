#pragma once
// A particle: one hypothesis of the sensor pose T_map_sensor, as six pose parameters, with its
// log-weight and the navigable cell it was last found in.

#include <vector>

#include "localizer/conic/pose.hpp"

namespace conicloc::localizer {

/// Pose parameters of T_map_sensor: position (metres, map frame) and ZYX Euler angles (radians),
/// R = Rz(yaw)·Ry(pitch)·Rx(roll) as in make_pose(). Index order of every 6-vector and 6×6
/// covariance in the localizer: x, y, z, roll, pitch, yaw.
struct PoseState {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
  double roll = 0.0;
  double pitch = 0.0;
  double yaw = 0.0;

  Pose3 to_pose() const { return make_pose(x, y, z, yaw, pitch, roll); }
};

/// The inverse of PoseState::to_pose() (yaw in (−π, π], pitch in [−π/2, π/2]).
PoseState pose_state_from(const Pose3& T_map_sensor);

struct Particle {
  PoseState state;
  double log_weight = 0.0;  ///< normalised so that the weights sum to one (log-sum-exp = 0)
  int cell = -1;  ///< index into PlaneMap::cells of the navigable cell holding x, y; -1 outside
  double floor_z = 0.0;  ///< floor under x, y in that cell (m), kept when it leaves every cell
  /// Rise of floor_z over the last motion prediction (m): the climb during the scan on a stair.
  double floor_rise_m = 0.0;
  /// Planar body velocity in the particle's own sensor frame (forward, left; m/s) and yaw rate
  /// (rad/s): part of the state when no odometry is given (MotionModel::predict_velocity).
  /// The planar velocity is the mean of what this particle's own displacements say of it, and
  /// velocity_variance (m²/s², per axis) what they leave open: a velocity no scan has yet seen
  /// stays open instead of being fixed to a draw that resampling would copy.
  double velocity_x = 0.0;
  double velocity_y = 0.0;
  double velocity_variance = 0.0;
  double yaw_rate = 0.0;
  /// The runner-up hypothesis the last resampling kept this particle in (1, 2, …), or 0: the rest
  /// of the cloud (runner_up_hypotheses.hpp). Roughening jitters each by its own extent.
  int hypothesis = 0;
};

using ParticleSet = std::vector<Particle>;

}  // namespace conicloc::localizer
