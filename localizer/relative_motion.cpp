#include "localizer/relative_motion.hpp"

#include <cmath>

namespace conicloc::localizer {

namespace {

Eigen::Matrix3d hat(const Eigen::Vector3d& w) {
  Eigen::Matrix3d W;
  W << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return W;
}

// The left Jacobian V(ω) of SO(3), t = V·ρ in exp of se(3) (Barfoot, State Estimation for
// Robotics, eq. 7.86): V = I + (1 − cos θ)/θ²·W + (θ − sin θ)/θ³·W², Taylor terms near θ = 0.
Eigen::Matrix3d left_jacobian(const Eigen::Vector3d& omega) {
  const double theta = omega.norm();
  const Eigen::Matrix3d W = hat(omega);
  double a, b;
  if (theta < 1e-6) {
    a = 0.5 - theta * theta / 24.0;
    b = 1.0 / 6.0 - theta * theta / 120.0;
  } else {
    a = (1.0 - std::cos(theta)) / (theta * theta);
    b = (theta - std::sin(theta)) / (theta * theta * theta);
  }
  return Eigen::Matrix3d::Identity() + a * W + b * W * W;
}

}  // namespace

Pose3 scale_motion(const Pose3& T_prev_curr, double fraction) {
  // exp(f·log T): constant body velocity (a screw motion), so scale(T, a)·scale(T, b) =
  // scale(T, a + b) exactly.
  const Eigen::AngleAxisd rotation(T_prev_curr.linear());
  const Eigen::Vector3d omega = rotation.angle() * rotation.axis();
  const Eigen::Vector3d rho = left_jacobian(omega).inverse() * T_prev_curr.translation();
  const Eigen::Vector3d omega_f = fraction * omega;
  Pose3 scaled = Pose3::Identity();
  const double angle = omega_f.norm();
  if (angle > 0.0) scaled.linear() = Eigen::AngleAxisd(angle, omega_f / angle).toRotationMatrix();
  scaled.translation() = left_jacobian(omega_f) * (fraction * rho);
  return scaled;
}

Pose3 interpolate_pose(const Pose3& a, const Pose3& b, double fraction) {
  return a * scale_motion(a.inverse() * b, fraction);
}

}  // namespace conicloc::localizer
