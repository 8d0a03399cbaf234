#include "localizer/conic/pose.hpp"

#include <algorithm>
#include <cmath>

namespace conicloc::localizer {

Pose3 make_pose(double x, double y, double z, double yaw, double pitch, double roll) {
  Pose3 pose = Pose3::Identity();
  pose.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  pose.translation() = Eigen::Vector3d(x, y, z);
  return pose;
}

RollPitchYaw roll_pitch_yaw(const Eigen::Matrix3d& R) {
  return {std::atan2(R(2, 1), R(2, 2)), std::asin(std::clamp(-R(2, 0), -1.0, 1.0)),
          std::atan2(R(1, 0), R(0, 0))};
}

Eigen::Matrix3d hat(const Eigen::Vector3d& w) {
  Eigen::Matrix3d W;
  W << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return W;
}

double yaw_of(const Pose3& pose) {
  const Eigen::Vector3d x_axis = pose.linear().col(0);
  return std::atan2(x_axis.y(), x_axis.x());
}

double angle_difference(double a, double b) {
  double d = std::remainder(a - b, 2.0 * M_PI);
  if (d <= -M_PI) d += 2.0 * M_PI;
  return d;
}

}  // namespace conicloc::localizer
