#include "localizer/conic/association_grid.hpp"

#include <algorithm>
#include <cmath>

namespace conicloc::localizer {

AssociationCellKey association_cell_of(const Pose3& T_map_sensor, double cell_m, double angle_rad) {
  const Eigen::Matrix3d& R = T_map_sensor.linear();
  const Eigen::Vector3d t = T_map_sensor.translation();
  // Z-Y-X Euler angles (make_pose's convention).
  const double yaw = std::atan2(R(1, 0), R(0, 0));
  const double pitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  const double roll = std::atan2(R(2, 1), R(2, 2));
  const auto bin = [](double value, double size) {
    return static_cast<std::int64_t>(std::round(value / size));  // cells centred on 0
  };
  return {bin(t.x(), cell_m),   bin(t.y(), cell_m),    bin(t.z(), cell_m),
          bin(roll, angle_rad), bin(pitch, angle_rad), bin(yaw, angle_rad)};
}

Pose3 association_cell_centre(const AssociationCellKey& key, double cell_m, double angle_rad) {
  const auto centre = [](std::int64_t index, double size) {
    return static_cast<double>(index) * size;
  };
  return make_pose(centre(key[0], cell_m), centre(key[1], cell_m), centre(key[2], cell_m),
                   centre(key[5], angle_rad), centre(key[4], angle_rad), centre(key[3], angle_rad));
}

}  // namespace conicloc::localizer
