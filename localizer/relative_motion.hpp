#pragma once
// Relative motions T_prev_curr between two sensor poses: scaling in time (constant velocity,
// de-skew) and interpolation of odometry.

#include "localizer/pose.hpp"

namespace conicloc::localizer {

/// The motion `fraction` times as long at the same constant body velocity (a screw motion):
/// exp(fraction · log T) on SE(3), so scale(T, a)·scale(T, b) = scale(T, a + b). Negative
/// fractions give the motion backwards in time. Rotations of π are ambiguous; scan-to-scan
/// motions are far below that.
Pose3 scale_motion(const Pose3& T_prev_curr, double fraction);

/// Pose interpolated between a (at fraction 0) and b (at fraction 1): a·scale_motion(a⁻¹b, f).
Pose3 interpolate_pose(const Pose3& a, const Pose3& b, double fraction);

}  // namespace conicloc::localizer
