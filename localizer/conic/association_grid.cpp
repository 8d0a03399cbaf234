#include "localizer/conic/association_grid.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace conicloc::localizer {

double AssociationCellSize::half_diagonal_m() const {
  return 0.5 * std::sqrt(2.0 * xy_m * xy_m + z_m * z_m);
}

double AssociationCellSize::range_margin_m(double range_m) const {
  return half_diagonal_m() + range_m * angle_rad;
}

AssociationGrid::AssociationGrid(const AssociationCellSize& size,
                                 std::vector<double> storey_floors_m)
    : size_(size), storey_floors_m_(std::move(storey_floors_m)) {}

AssociationCellKey AssociationGrid::cell_of(const Pose3& T_map_sensor) const {
  const Eigen::Vector3d t = T_map_sensor.translation();
  const auto [roll, pitch, yaw] = roll_pitch_yaw(T_map_sensor.linear());
  const auto bin = [](double value, double cell) {
    return static_cast<std::int64_t>(std::round(value / cell));  // cells centred on 0
  };
  // The storey: the last floor at or below the sensor (−1 below every floor, counted from 0).
  const auto above = std::upper_bound(storey_floors_m_.begin(), storey_floors_m_.end(), t.z());
  const std::int64_t storey = static_cast<std::int64_t>(above - storey_floors_m_.begin()) - 1;
  const double floor_z = storey >= 0 ? storey_floors_m_[static_cast<std::size_t>(storey)] : 0.0;
  return {bin(t.x(), size_.xy_m),          bin(t.y(), size_.xy_m),     storey,
          bin(t.z() - floor_z, size_.z_m), bin(roll, size_.angle_rad), bin(pitch, size_.angle_rad),
          bin(yaw, size_.angle_rad)};
}

Pose3 AssociationGrid::centre(const AssociationCellKey& key) const {
  const auto centre = [](std::int64_t index, double cell) {
    return static_cast<double>(index) * cell;
  };
  const double floor_z = key[2] >= 0 ? storey_floors_m_[static_cast<std::size_t>(key[2])] : 0.0;
  return make_pose(centre(key[0], size_.xy_m), centre(key[1], size_.xy_m),
                   floor_z + centre(key[3], size_.z_m), centre(key[6], size_.angle_rad),
                   centre(key[5], size_.angle_rad), centre(key[4], size_.angle_rad));
}

AssociationGrid association_grid(const maps::PlaneMap& map, const AssociationCellSize& size) {
  std::vector<double> floors;
  for (const maps::Storey& storey : map.storeys) floors.push_back(storey.floor_z);
  std::sort(floors.begin(), floors.end());
  return AssociationGrid(size, std::move(floors));
}

}  // namespace conicloc::localizer
