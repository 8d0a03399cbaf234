#include "localizer/filter/particle.hpp"

#include <algorithm>
#include <cmath>

namespace conicloc::localizer {

PoseState pose_state_from(const Pose3& T_map_sensor) {
  // ZYX Euler angles of R = Rz(yaw)·Ry(pitch)·Rx(roll): R(2,0) = −sin(pitch),
  // R(2,1) = cos(pitch)·sin(roll), R(2,2) = cos(pitch)·cos(roll), R(1,0)/R(0,0) = tan(yaw).
  const Eigen::Matrix3d& R = T_map_sensor.linear();
  PoseState state;
  state.x = T_map_sensor.translation().x();
  state.y = T_map_sensor.translation().y();
  state.z = T_map_sensor.translation().z();
  state.pitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  state.roll = std::atan2(R(2, 1), R(2, 2));
  state.yaw = std::atan2(R(1, 0), R(0, 0));
  return state;
}

}  // namespace conicloc::localizer
