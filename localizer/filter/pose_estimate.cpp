#include "localizer/filter/pose_estimate.hpp"

#include <algorithm>
#include <cmath>

namespace conicloc::localizer {

namespace {

Vector6 difference(const PoseState& a, const PoseState& b) {
  Vector6 d;
  d << a.x - b.x, a.y - b.y, a.z - b.z, angle_difference(a.roll, b.roll),
      angle_difference(a.pitch, b.pitch), angle_difference(a.yaw, b.yaw);
  return d;
}

}  // namespace

PoseEstimate estimate_pose(const ParticleSet& particles, const PoseEstimateConfig& config) {
  PoseEstimate estimate;
  if (particles.empty()) return estimate;
  const auto best = std::max_element(
      particles.begin(), particles.end(),
      [](const Particle& a, const Particle& b) { return a.log_weight < b.log_weight; });
  const PoseState& anchor = best->state;
  // Weighted mean of the mode: linear for x, y, z; about the anchor for the angles, which
  // is the circular mean for the small spreads inside a mode.
  Vector6 sum = Vector6::Zero();
  double mass = 0.0;
  for (const Particle& p : particles) {
    const Vector6 d = difference(p.state, anchor);
    if (std::hypot(d(0), d(1)) > config.mode_radius_m || std::abs(d(5)) > config.mode_yaw_rad)
      continue;
    const double w = std::exp(p.log_weight);
    sum += w * d;
    mass += w;
  }
  PoseState mean = anchor;
  if (mass > 0.0) {
    const Vector6 offset = sum / mass;
    mean.x += offset(0);
    mean.y += offset(1);
    mean.z += offset(2);
    mean.roll = angle_difference(mean.roll + offset(3), 0.0);
    mean.pitch = angle_difference(mean.pitch + offset(4), 0.0);
    mean.yaw = angle_difference(mean.yaw + offset(5), 0.0);
  }
  Matrix6 covariance = Matrix6::Zero();
  double total = 0.0;
  for (const Particle& p : particles) {
    const double w = std::exp(p.log_weight);
    const Vector6 d = difference(p.state, mean);
    covariance.noalias() += w * d * d.transpose();
    total += w;
  }
  estimate.state = mean;
  estimate.covariance = total > 0.0 ? Matrix6(covariance / total) : covariance;
  estimate.mode_weight = total > 0.0 ? mass / total : 0.0;
  return estimate;
}

}  // namespace conicloc::localizer
