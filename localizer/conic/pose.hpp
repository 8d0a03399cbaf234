#pragma once
// Sensor poses T_map_sensor = (R, t): a point p_s in the sensor frame is R·p_s + t in the map.

#include <Eigen/Geometry>

namespace conicloc::localizer {

using Pose3 = Eigen::Isometry3d;

/// R = Rz(yaw)·Ry(pitch)·Rx(roll) (ZYX, REP-103), angles in radians.
Pose3 make_pose(double x, double y, double z, double yaw, double pitch = 0.0, double roll = 0.0);

/// The Z-Y-X angles of R (make_pose's convention), radians: R(2,1) = cos(pitch)·sin(roll),
/// R(2,2) = cos(pitch)·cos(roll), R(2,0) = −sin(pitch), R(1,0)/R(0,0) = tan(yaw).
struct RollPitchYaw {
  double roll = 0.0;
  double pitch = 0.0;
  double yaw = 0.0;
};
RollPitchYaw roll_pitch_yaw(const Eigen::Matrix3d& R);

/// [w]×, the matrix of the cross product: hat(w)·v = w × v.
Eigen::Matrix3d hat(const Eigen::Vector3d& w);

/// Yaw of a pose's x axis about the map z axis, radians in (−π, π].
double yaw_of(const Pose3& pose);

/// Smallest signed difference a − b of two angles, radians in (−π, π].
double angle_difference(double a, double b);

}  // namespace conicloc::localizer
