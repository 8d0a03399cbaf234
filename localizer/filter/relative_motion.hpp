#pragma once
// Relative motions T_prev_curr between two sensor poses: scaling in time (constant velocity,
// de-skew) and interpolation of odometry.

#include <vector>

#include "localizer/conic/pose.hpp"

namespace conicloc::localizer {

/// The motion `fraction` times as long at the same constant body velocity (a screw motion):
/// exp(fraction · log T) on SE(3), so scale(T, a)·scale(T, b) = scale(T, a + b). Negative
/// fractions give the motion backwards in time. Rotations of π are ambiguous; scan-to-scan
/// motions are far below that.
Pose3 scale_motion(const Pose3& T_prev_curr, double fraction);

/// scale_motion() for many fractions of one motion (de-skew: one per return): the logarithm
/// ξ = (ρ, ω) = log T is taken once, and each fraction f costs one sincos for exp(f·ξ).
class ConstantVelocityMotion {
 public:
  explicit ConstantVelocityMotion(const Pose3& T_prev_curr);
  /// exp(fraction · log T).
  Pose3 at(double fraction) const;
  /// θ, the angle of the whole motion's rotation.
  double angle() const { return angle_; }
  /// ρ, the translation part of log T (the body velocity times the interval).
  const Eigen::Vector3d& rho() const { return rho_; }

 private:
  Eigen::Vector3d axis_ = Eigen::Vector3d::UnitZ();  ///< ω/θ (any unit vector when θ = 0)
  double angle_ = 0.0;                               ///< θ = |ω|
  Eigen::Vector3d rho_ = Eigen::Vector3d::Zero();    ///< ρ = V(ω)⁻¹ t
  Eigen::Matrix3d K_ = Eigen::Matrix3d::Zero();      ///< hat(axis_), taken once
  Eigen::Matrix3d K2_ = Eigen::Matrix3d::Zero();     ///< its square
};

/// ConstantVelocityMotion for the tens of thousands of fractions of one scan (de-skew: one per
/// return): the motion taken at knots evenly spaced over [lo, hi], each fraction's pose
/// interpolated linearly between the two knots about it, entry by entry of [R | t] — twelve
/// products instead of a sincos and a screw motion. A chord departs from its curve by an eighth of
/// the curve's second derivative times the knots' spacing Δf squared: the rotation's by
/// (θΔf)²/8, kept ≤ 1.25·10⁻⁹ rad (0.125 µm at 100 m) by knots at most δ = θΔf = 10⁻⁴ rad of turn
/// apart; the translation's, t(f) = V(fω)·fρ, by ≤ θ|ρ|·Δf²/8, kept ≤ 10 nm. Fractions outside
/// [lo, hi] extrapolate the end knots' chords. Where that takes more than 2,048 intervals (a turn
/// over 0.2 rad, or a span that holds an outlier), or [lo, hi] is not finite, no table is built
/// and every fraction takes the exact motion.
class TabulatedMotion {
 public:
  TabulatedMotion(const ConstantVelocityMotion& motion, double lo, double hi);
  /// T(fraction)·p.
  Eigen::Vector3d apply(double fraction, const Eigen::Vector3d& p) const;
  /// The yaw of T(fraction): atan2(R₁₀, R₀₀).
  double yaw(double fraction) const;

 private:
  using Entries = Eigen::Matrix<double, 3, 4>;  ///< [R | t]
  Entries at(double fraction) const;

  ConstantVelocityMotion exact_;
  double lo_ = 0.0;
  double step_ = 1.0;                ///< between knots, in fraction
  std::vector<Entries> knots_;       ///< T at lo + k·step; empty: exact_ for every fraction
  std::vector<Entries> increments_;  ///< knots_[k + 1] − knots_[k]
};

/// Pose interpolated between a (at fraction 0) and b (at fraction 1): a·scale_motion(a⁻¹b, f).
Pose3 interpolate_pose(const Pose3& a, const Pose3& b, double fraction);

}  // namespace conicloc::localizer
