#include "sim/odometry_drift.hpp"

#include <cmath>

namespace conicloc::sim {

std::vector<io::StampedPose> simulate_odometry(const Trajectory& trajectory, double duration_s,
                                               double time_offset_s, const OdometryConfig& config,
                                               std::mt19937_64& rng) {
  std::normal_distribution<double> unit(0.0, 1.0);
  const double dt = 1.0 / config.rate_hz;
  const double scale = 1.0 + config.speed_scale_sigma * unit(rng);
  double bias = config.yaw_rate_bias_radps * unit(rng);
  const int steps = static_cast<int>(std::floor(duration_s * config.rate_hz + 1e-9));

  std::vector<io::StampedPose> poses;
  Eigen::Isometry3d truth = trajectory.T_map_sensor(0.0);
  Eigen::Vector2d xy = truth.translation().head<2>();
  double yaw = std::atan2(truth.linear()(1, 0), truth.linear()(0, 0));
  for (int i = 0; i <= steps; ++i) {
    const double t = i * dt;
    const Eigen::Isometry3d now = trajectory.T_map_sensor(t);
    if (i > 0) {
      // True increments of the sensor over the step, measured with errors.
      const Eigen::Vector2d moved = now.translation().head<2>() - truth.translation().head<2>();
      const double true_yaw_now = std::atan2(now.linear()(1, 0), now.linear()(0, 0));
      const double true_yaw_before = std::atan2(truth.linear()(1, 0), truth.linear()(0, 0));
      const double true_rate = std::remainder(true_yaw_now - true_yaw_before, 2.0 * M_PI) / dt;
      // Signed speed along the true heading (the sensor may move sideways when hand-held).
      const double forward =
          moved.dot(Eigen::Vector2d(std::cos(true_yaw_before), std::sin(true_yaw_before)));
      const double lateral =
          moved.dot(Eigen::Vector2d(-std::sin(true_yaw_before), std::cos(true_yaw_before)));
      const bool moving = moved.norm() > 1e-6;
      const double speed = moving ? scale * forward / dt + config.speed_noise_mps * unit(rng) : 0.0;
      bias += config.yaw_rate_bias_walk * std::sqrt(dt) * unit(rng);
      const double rate = true_rate + bias + config.yaw_rate_noise_radps * unit(rng);
      const double mid_yaw = yaw + 0.5 * rate * dt;
      xy += Eigen::Vector2d(std::cos(mid_yaw), std::sin(mid_yaw)) * speed * dt +
            Eigen::Vector2d(-std::sin(mid_yaw), std::cos(mid_yaw)) * scale * lateral;
      yaw += rate * dt;
      truth = now;
    }
    // Roll and pitch from the truth: R = Rz(ψ_odo)·Rz(−ψ_true)·R_true keeps them.
    const double true_yaw = std::atan2(now.linear()(1, 0), now.linear()(0, 0));
    io::StampedPose pose;
    pose.time_s = time_offset_s + t;
    pose.pose.linear() =
        Eigen::AngleAxisd(yaw - true_yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
        now.linear();
    pose.pose.translation() = Eigen::Vector3d(xy.x(), xy.y(), now.translation().z());
    poses.push_back(pose);
  }
  return poses;
}

}  // namespace conicloc::sim
