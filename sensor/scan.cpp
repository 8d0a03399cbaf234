#include "sensor/scan.hpp"

#include <cmath>

namespace conicloc::sensor {

std::size_t Scan::valid_returns() const {
  std::size_t count = 0;
  for (const auto& ring : rings) {
    for (const auto& ret : ring.returns) count += ret.status == ReturnStatus::Valid ? 1 : 0;
  }
  return count;
}

Eigen::Vector3d sensor_point(const RingScan& ring, const Return& ret) {
  const double horizontal = ret.range_m * std::cos(ring.elevation_rad);
  return {horizontal * std::cos(ret.azimuth_rad), horizontal * std::sin(ret.azimuth_rad),
          ring.vertical_offset_m + ret.range_m * std::sin(ring.elevation_rad)};
}

Eigen::Matrix3Xd sensor_points(const Scan& scan) {
  Eigen::Matrix3Xd points(3, static_cast<Eigen::Index>(scan.valid_returns()));
  Eigen::Index column = 0;
  for (const auto& ring : scan.rings) {
    for (const auto& ret : ring.returns) {
      if (ret.status == ReturnStatus::Valid) points.col(column++) = sensor_point(ring, ret);
    }
  }
  return points;
}

}  // namespace conicloc::sensor
