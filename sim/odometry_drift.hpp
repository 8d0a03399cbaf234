#pragma once
// Wheel / IMU odometry with realistic drift, integrated from the true motion of a Trajectory:
// speed with a scale error and white noise (wheels), yaw rate with a bias that random-walks and
// white noise (gyro). Dead reckoning in the plane: x += v cos ψ dt, y += v sin ψ dt, ψ += ω dt.
// The odometry frame is the map frame at the start (the first pose is the true one); z, roll and
// pitch are taken from the truth (a barometer / the gravity vector observe them without drift).

#include <random>
#include <vector>

#include "io/tum_trajectory.hpp"
#include "sim/trajectory.hpp"

namespace conicloc::sim {

struct OdometryConfig {
  double rate_hz = 50.0;
  double speed_scale_sigma = 0.01;      ///< wheel radius error, drawn once
  double speed_noise_mps = 0.02;        ///< white, per sample
  double yaw_rate_bias_radps = 0.002;   ///< σ of the initial gyro bias
  double yaw_rate_bias_walk = 2e-4;     ///< bias random walk, rad/s per √s
  double yaw_rate_noise_radps = 0.005;  ///< white, per sample
};

/// Odometry poses from time 0 to `duration_s`, stamped `time_offset_s + t`.
std::vector<io::StampedPose> simulate_odometry(const Trajectory& trajectory, double duration_s,
                                               double time_offset_s, const OdometryConfig& config,
                                               std::mt19937_64& rng);

}  // namespace conicloc::sim
