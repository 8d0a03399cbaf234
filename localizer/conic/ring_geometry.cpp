#include "localizer/conic/ring_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace conicloc::localizer {

Eigen::Vector3d RingGeometry::direction(double azimuth_rad) const {
  return {cos_elevation * std::cos(azimuth_rad), cos_elevation * std::sin(azimuth_rad),
          sin_elevation};
}

Eigen::Vector3d RingGeometry::point(double azimuth_rad, double range_m) const {
  return apex() + range_m * direction(azimuth_rad);
}

RingGeometry make_ring_geometry(double elevation_rad, double vertical_offset_m, int ring,
                                int channel) {
  RingGeometry geometry;
  geometry.ring = ring;
  geometry.channel = channel;
  geometry.elevation_rad = elevation_rad;
  geometry.vertical_offset_m = vertical_offset_m;
  geometry.cos_elevation = std::cos(elevation_rad);
  geometry.sin_elevation = std::sin(elevation_rad);
  return geometry;
}

std::vector<RingGeometry> ring_geometry(const sensor::LaserCalibration& calibration) {
  std::vector<RingGeometry> rings;
  rings.reserve(calibration.lasers.size());
  for (std::size_t channel = 0; channel < calibration.lasers.size(); ++channel) {
    const sensor::Laser& laser = calibration.lasers[channel];
    rings.push_back(make_ring_geometry(laser.elevation_rad, laser.vertical_offset_m, laser.ring,
                                       static_cast<int>(channel)));
  }
  std::sort(rings.begin(), rings.end(),
            [](const RingGeometry& a, const RingGeometry& b) { return a.ring < b.ring; });
  return rings;
}

}  // namespace conicloc::localizer
