#include "localizer/filter/relative_motion.hpp"

#include <algorithm>
#include <cmath>

namespace conicloc::localizer {

namespace {

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

ConstantVelocityMotion::ConstantVelocityMotion(const Pose3& T_prev_curr) {
  const Eigen::AngleAxisd rotation(T_prev_curr.linear());
  angle_ = rotation.angle();
  if (angle_ > 0.0) axis_ = rotation.axis();
  rho_ = left_jacobian(angle_ * axis_).inverse() * T_prev_curr.translation();
  K_ = hat(axis_);
  K2_ = K_ * K_;
}

Pose3 ConstantVelocityMotion::at(double fraction) const {
  // exp(f·ξ): R = I + sin φ·K + (1 − cos φ)·K² (Rodrigues, K = hat(axis), φ = fθ) and t = V(fω)·fρ,
  // V as in left_jacobian; both from the one sincos of φ.
  const double phi = fraction * angle_;
  const double sin_phi = std::sin(phi), cos_phi = std::cos(phi);
  double a, b;  // V = I + a·K + b·K², a = (1 − cos φ)/φ, b = (φ − sin φ)/φ (W = φK)
  if (std::abs(phi) < 1e-6) {
    a = phi / 2.0 - phi * phi * phi / 24.0;
    b = phi * phi / 6.0 - phi * phi * phi * phi / 120.0;
  } else {
    a = (1.0 - cos_phi) / phi;
    b = (phi - sin_phi) / phi;
  }
  Pose3 scaled = Pose3::Identity();
  scaled.linear() = Eigen::Matrix3d::Identity() + sin_phi * K_ + (1.0 - cos_phi) * K2_;
  scaled.translation() = (Eigen::Matrix3d::Identity() + a * K_ + b * K2_) * (fraction * rho_);
  return scaled;
}

TabulatedMotion::TabulatedMotion(const ConstantVelocityMotion& motion, double lo, double hi)
    : exact_(motion), lo_(lo) {
  constexpr double kMaxTurnRad = 1e-4;            // δ = θΔf between knots
  constexpr double kMaxTranslationErrorM = 1e-8;  // θ|ρ|·Δf²/8
  constexpr double kMaxIntervals = 2048;          // 393 KB of knots and increments
  const double span = std::max(hi - lo, 0.0);
  const double theta = motion.angle();
  const double for_rotation = theta * span / kMaxTurnRad;
  const double for_translation =
      span * std::sqrt(theta * motion.rho().norm() / (8.0 * kMaxTranslationErrorM));
  const double needed = std::ceil(std::max(for_rotation, for_translation));
  if (!std::isfinite(lo) || !(needed <= kMaxIntervals)) return;  // the exact motion throughout
  const int intervals = static_cast<int>(std::max(needed, 1.0));
  step_ = span > 0.0 ? span / intervals : 1.0;
  knots_.resize(static_cast<std::size_t>(intervals) + 1);
  for (std::size_t k = 0; k < knots_.size(); ++k) {
    knots_[k] = motion.at(lo_ + static_cast<double>(k) * step_).matrix().topRows<3>();
  }
  increments_.resize(static_cast<std::size_t>(intervals));
  for (std::size_t k = 0; k < increments_.size(); ++k) increments_[k] = knots_[k + 1] - knots_[k];
}

TabulatedMotion::Entries TabulatedMotion::at(double fraction) const {
  if (knots_.empty()) return exact_.at(fraction).matrix().topRows<3>();
  const double u = (fraction - lo_) / step_;
  const double last = static_cast<double>(increments_.size() - 1);
  // A fraction that is not a number gives a pose that is not one (as the exact motion's), not an
  // index out of the table.
  const double k = std::isnan(u) ? 0.0 : std::clamp(std::floor(u), 0.0, last);
  const auto index = static_cast<std::size_t>(k);
  return knots_[index] + (u - k) * increments_[index];
}

Eigen::Vector3d TabulatedMotion::apply(double fraction, const Eigen::Vector3d& p) const {
  const Entries T = at(fraction);
  return T.leftCols<3>() * p + T.col(3);
}

double TabulatedMotion::yaw(double fraction) const {
  const Entries T = at(fraction);
  return std::atan2(T(1, 0), T(0, 0));
}

Pose3 scale_motion(const Pose3& T_prev_curr, double fraction) {
  // exp(f·log T): constant body velocity (a screw motion), so scale(T, a)·scale(T, b) =
  // scale(T, a + b) exactly.
  return ConstantVelocityMotion(T_prev_curr).at(fraction);
}

Pose3 interpolate_pose(const Pose3& a, const Pose3& b, double fraction) {
  return a * scale_motion(a.inverse() * b, fraction);
}

}  // namespace conicloc::localizer
