#include "io/cloud_scan.hpp"

#include <algorithm>
#include <cmath>

namespace conicloc::io {
namespace {

const PointField& required_field(const PointCloud2View& cloud, const char* name) {
  const PointField* field = cloud.field(name);
  if (!field) throw MessageError(std::string("PointCloud2 has no field '") + name + "'");
  return *field;
}

// The laser whose elevation, seen from its own apex, is nearest to the point's.
std::size_t nearest_laser(const sensor::LaserCalibration& calibration, double x, double y,
                          double z) {
  const double horizontal = std::hypot(x, y);
  std::size_t best = 0;
  double best_error = INFINITY;
  for (std::size_t k = 0; k < calibration.lasers.size(); ++k) {
    const auto& laser = calibration.lasers[k];
    const double error =
        std::abs(std::atan2(z - laser.vertical_offset_m, horizontal) - laser.elevation_rad);
    if (error < best_error) {
      best_error = error;
      best = k;
    }
  }
  return best;
}

}  // namespace

double azimuth_gap_rad(const sensor::Scan& scan) {
  std::vector<double> azimuths;
  for (const auto& ring : scan.rings) {
    for (const auto& ret : ring.returns) azimuths.push_back(ret.azimuth_rad);
  }
  if (azimuths.empty()) return 2.0 * M_PI;
  std::sort(azimuths.begin(), azimuths.end());
  double gap = azimuths.front() + 2.0 * M_PI - azimuths.back();
  for (std::size_t i = 1; i < azimuths.size(); ++i)
    gap = std::max(gap, azimuths[i] - azimuths[i - 1]);
  return gap;
}

sensor::Scan cloud_to_scan(const PointCloud2View& cloud,
                           const sensor::LaserCalibration& calibration, double time_origin_s,
                           const CloudScanConfig& config) {
  const PointField& x_field = required_field(cloud, "x");
  const PointField& y_field = required_field(cloud, "y");
  const PointField& z_field = required_field(cloud, "z");
  const PointField* ring_field = cloud.field("ring");
  const PointField* time_field = cloud.field("time");
  const PointField* intensity_field = cloud.field("intensity");
  // The ring field numbers lasers by elevation rank: the calibration's laser of each rank.
  std::vector<std::size_t> laser_of_ring(calibration.lasers.size());
  for (std::size_t k = 0; k < calibration.lasers.size(); ++k)
    laser_of_ring[static_cast<std::size_t>(calibration.lasers[k].ring)] = k;

  sensor::Scan scan = sensor::empty_scan(calibration);
  const double stamp_s = cloud.stamp_s - time_origin_s;
  for (std::size_t i = 0; i < cloud.point_count(); ++i) {
    const double x = cloud.value(x_field, i);
    const double y = cloud.value(y_field, i);
    const double z = cloud.value(z_field, i);
    const double time_s = time_field ? cloud.value(*time_field, i) : 0.0;
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z) || !std::isfinite(time_s))
      continue;
    if (x == 0.0 && y == 0.0 && z == 0.0) continue;  // a driver's placeholder for no return
    std::size_t laser = 0;
    if (ring_field) {
      const double ring = cloud.value(*ring_field, i);
      if (!(ring >= 0.0 && ring < static_cast<double>(calibration.lasers.size()))) {
        throw MessageError("PointCloud2 point " + std::to_string(i) + " has ring " +
                           std::to_string(ring) + ", the sensor has " +
                           std::to_string(calibration.lasers.size()) + " lasers");
      }
      laser = laser_of_ring[static_cast<std::size_t>(ring)];
    } else {
      laser = nearest_laser(calibration, x, y, z);
    }
    const auto& calibrated = calibration.lasers[laser];
    sensor::Return ret;
    double azimuth = std::atan2(y, x);
    if (azimuth < 0.0) azimuth += 2.0 * M_PI;
    ret.azimuth_rad = azimuth >= 2.0 * M_PI ? 0.0 : azimuth;
    ret.range_m = std::sqrt(x * x + y * y + std::pow(z - calibrated.vertical_offset_m, 2));
    ret.time_s = stamp_s + time_s;
    if (intensity_field) {
      const double intensity = cloud.value(*intensity_field, i);
      ret.intensity = intensity >= 0.0 ? static_cast<std::uint8_t>(std::min(intensity, 255.0)) : 0;
    }
    if (ret.range_m > config.max_range_m) ret.status = sensor::ReturnStatus::OutOfRange;
    scan.rings[static_cast<std::size_t>(calibrated.ring)].returns.push_back(ret);
  }

  if (!sensor::sort_rings_and_time(scan)) scan.start_time_s = scan.end_time_s = stamp_s;
  scan.partial = azimuth_gap_rad(scan) > config.max_gap_rad;
  return scan;
}

}  // namespace conicloc::io
