#pragma once
// Relative motions T_prev_curr between two sensor poses: scaling in time (constant velocity,
// de-skew) and interpolation of odometry.

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

 private:
  Eigen::Vector3d axis_ = Eigen::Vector3d::UnitZ();  ///< ω/θ (any unit vector when θ = 0)
  double angle_ = 0.0;                               ///< θ = |ω|
  Eigen::Vector3d rho_ = Eigen::Vector3d::Zero();    ///< ρ = V(ω)⁻¹ t
  Eigen::Matrix3d K_ = Eigen::Matrix3d::Zero();      ///< hat(axis_), taken once
  Eigen::Matrix3d K2_ = Eigen::Matrix3d::Zero();     ///< its square
};

/// Pose interpolated between a (at fraction 0) and b (at fraction 1): a·scale_motion(a⁻¹b, f).
Pose3 interpolate_pose(const Pose3& a, const Pose3& b, double fraction);

}  // namespace conicloc::localizer
