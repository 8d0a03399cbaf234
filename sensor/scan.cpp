#include "sensor/scan.hpp"

#include <algorithm>
#include <cmath>

namespace conicloc::sensor {

std::size_t Scan::valid_returns() const {
  std::size_t count = 0;
  for (const auto& ring : rings) {
    for (const auto& ret : ring.returns) count += ret.status == ReturnStatus::Valid ? 1 : 0;
  }
  return count;
}

Scan empty_scan(const LaserCalibration& calibration) {
  Scan scan;
  scan.rings.resize(calibration.lasers.size());
  for (std::size_t k = 0; k < calibration.lasers.size(); ++k) {
    const auto& laser = calibration.lasers[k];
    auto& ring = scan.rings[static_cast<std::size_t>(laser.ring)];
    ring.ring = laser.ring;
    ring.channel = static_cast<int>(k);
    ring.elevation_rad = laser.elevation_rad;
    ring.vertical_offset_m = laser.vertical_offset_m;
  }
  return scan;
}

bool sort_rings_and_time(Scan& scan) {
  bool first = true;
  for (auto& ring : scan.rings) {
    std::stable_sort(
        ring.returns.begin(), ring.returns.end(),
        [](const Return& a, const Return& b) { return a.azimuth_rad < b.azimuth_rad; });
    for (const auto& ret : ring.returns) {
      scan.start_time_s = first ? ret.time_s : std::min(scan.start_time_s, ret.time_s);
      scan.end_time_s = first ? ret.time_s : std::max(scan.end_time_s, ret.time_s);
      first = false;
    }
  }
  return !first;
}

Eigen::Vector3d sensor_point(const RingScan& ring, const Return& ret) {
  return sensor_point(ring, ret, std::cos(ring.elevation_rad), std::sin(ring.elevation_rad));
}

Eigen::Vector3d sensor_point(const RingScan& ring, const Return& ret, double cos_elevation,
                             double sin_elevation) {
  const double horizontal = ret.range_m * cos_elevation;
  return {horizontal * std::cos(ret.azimuth_rad), horizontal * std::sin(ret.azimuth_rad),
          ring.vertical_offset_m + ret.range_m * sin_elevation};
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
