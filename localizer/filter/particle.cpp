#include "localizer/filter/particle.hpp"

namespace conicloc::localizer {

PoseState pose_state_from(const Pose3& T_map_sensor) {
  const RollPitchYaw angles = roll_pitch_yaw(T_map_sensor.linear());
  PoseState state;
  state.x = T_map_sensor.translation().x();
  state.y = T_map_sensor.translation().y();
  state.z = T_map_sensor.translation().z();
  state.pitch = angles.pitch;
  state.roll = angles.roll;
  state.yaw = angles.yaw;
  return state;
}

}  // namespace conicloc::localizer
