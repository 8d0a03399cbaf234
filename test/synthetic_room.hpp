#pragma once
// Test scenes for the localizer: a box room with a pillar as a PlaneMap, and synthetic VLP-16
// scans of it from a small brute-force ray cast (independent of the localizer's models).

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>

#include "localizer/conic/pose.hpp"
#include "localizer/filter/motion_model.hpp"
#include "localizer/filter/particle.hpp"
#include "localizer/filter/relative_motion.hpp"
#include "maps/plane_map.hpp"
#include "sensor/builtin_calibration.hpp"
#include "sensor/scan.hpp"

namespace conicloc::test {

/// A particle standing at (x, y, z) with heading `yaw`, nothing else set.
inline localizer::Particle particle_at(double x, double y, double yaw, double z = 1.2) {
  localizer::Particle p;
  p.state.x = x;
  p.state.y = y;
  p.state.z = z;
  p.state.yaw = yaw;
  return p;
}

/// A motion model without noise (every std. dev. 0), the sensor `height_m` above the floor.
inline localizer::MotionModelConfig noiseless_motion(double height_m) {
  localizer::MotionModelConfig config;
  config.xy_sigma_m_per_sqrt_s = 0.0;
  config.xy_sigma_per_m = 0.0;
  config.yaw_sigma_rad_per_sqrt_s = 0.0;
  config.yaw_sigma_per_rad = 0.0;
  config.yaw_sigma_rad_per_m = 0.0;
  config.z_sigma_m = 0.0;
  config.roll_sigma_rad = 0.0;
  config.pitch_sigma_rad = 0.0;
  config.velocity_sigma_m_s = 0.0;
  config.yaw_rate_sigma_rad_s = 0.0;
  config.height_above_floor_m = height_m;
  return config;
}

/// The built-in VLP-16 calibration.
inline const sensor::LaserCalibration& vlp16() {
  static const auto calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  return calibration;
}

/// Adds the quad a-b-c-d (normal by the right-hand rule) to `map` as part of `cell`.
inline void add_quad(maps::PlaneMap& map, int cell, const Eigen::Vector3d& a,
                     const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  maps::PlanarPolygon polygon;
  if (!maps::make_planar_polygon({a, b, c, d}, {}, polygon)) return;
  polygon.cell = cell;
  polygon.storey = 0;
  map.cells[cell].polygons.push_back(static_cast<int>(map.polygons.size()));
  map.bounds.extend(polygon.bounds);
  map.polygons.push_back(std::move(polygon));
}

/// Axis-aligned box [lo, hi] with faces facing inward (a room) or outward (a pillar).
inline void add_box(maps::PlaneMap& map, int cell, const Eigen::Vector3d& lo,
                    const Eigen::Vector3d& hi, bool inward) {
  const auto v = [&](int ix, int iy, int iz) {
    return Eigen::Vector3d(ix ? hi.x() : lo.x(), iy ? hi.y() : lo.y(), iz ? hi.z() : lo.z());
  };
  const auto quad = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                        const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
    if (inward)
      add_quad(map, cell, a, b, c, d);
    else
      add_quad(map, cell, d, c, b, a);
  };
  quad(v(0, 0, 0), v(1, 0, 0), v(1, 1, 0), v(0, 1, 0));  // floor, +z
  quad(v(0, 0, 1), v(0, 1, 1), v(1, 1, 1), v(1, 0, 1));  // ceiling, −z
  quad(v(0, 0, 0), v(0, 1, 0), v(0, 1, 1), v(0, 0, 1));  // x = lo, +x
  quad(v(1, 0, 0), v(1, 0, 1), v(1, 1, 1), v(1, 1, 0));  // x = hi, −x
  quad(v(0, 0, 0), v(0, 0, 1), v(1, 0, 1), v(1, 0, 0));  // y = lo, +y
  quad(v(0, 1, 0), v(1, 1, 0), v(1, 1, 1), v(0, 1, 1));  // y = hi, −y
}

/// An empty room [0, size] (floor at z = 0) as one navigable cell `id` on one storey.
inline maps::PlaneMap make_empty_room(const std::string& id, const Eigen::Vector3d& size) {
  maps::PlaneMap map;
  map.storeys.push_back({"ground", 0.0, size.z()});
  maps::Cell cell;
  cell.id = id;
  cell.storey = 0;
  cell.footprint = {{0, 0}, {size.x(), 0}, {size.x(), size.y()}, {0, size.y()}};
  cell.bounds = Eigen::AlignedBox3d(Eigen::Vector3d::Zero(), size);
  cell.floor_z = 0.0;
  cell.ceiling_z = size.z();
  cell.representative_point = {0.5 * size.x(), 0.5 * size.y(), 0};
  map.cells.push_back(cell);
  add_box(map, 0, Eigen::Vector3d::Zero(), size, true);
  return map;
}

/// A 10 m × 6 m × 3 m room (floor at z = 0) with a 1 m × 0.6 m pillar off-centre, which breaks
/// the room's symmetry, as one navigable cell on one storey.
inline maps::PlaneMap make_box_room() {
  maps::PlaneMap map = make_empty_room("room", {10, 6, 3});
  add_box(map, 0, {7.0, 1.0, 0.0}, {8.0, 1.6, 3.0}, false);
  return map;
}

/// A storey over `map`'s (floor at `floor_z`, 3 m to its ceiling) holding one room of `size_xy`
/// from the origin, with make_box_room()'s pillar if `pillar`; a navigable cell.
inline void add_room_storey(maps::PlaneMap& map, double floor_z, const Eigen::Vector2d& size_xy,
                            bool pillar) {
  const int storey = static_cast<int>(map.storeys.size());
  const int cell = static_cast<int>(map.cells.size());
  map.storeys.push_back({"storey " + std::to_string(storey), floor_z, floor_z + 3.0});
  maps::Cell room = map.cells[0];
  room.id = "room on storey " + std::to_string(storey);
  room.storey = storey;
  room.polygons.clear();
  room.footprint = {{0, 0}, {size_xy.x(), 0}, {size_xy.x(), size_xy.y()}, {0, size_xy.y()}};
  room.bounds = Eigen::AlignedBox3d(Eigen::Vector3d(0, 0, floor_z),
                                    Eigen::Vector3d(size_xy.x(), size_xy.y(), floor_z + 3.0));
  room.floor_z = floor_z;
  room.ceiling_z = floor_z + 3.0;
  room.representative_point = Eigen::Vector3d(size_xy.x() / 2, size_xy.y() / 2, floor_z);
  map.cells.push_back(room);
  add_box(map, cell, {0, 0, floor_z}, {size_xy.x(), size_xy.y(), floor_z + 3.0}, true);
  if (pillar) add_box(map, cell, {7.0, 1.0, floor_z}, {8.0, 1.6, floor_z + 3.0}, false);
}

/// `storeys` copies of make_box_room() stacked `storey_m` apart (floor to floor): one place
/// stands at one x, y on each.
inline maps::PlaneMap make_identical_storeys(double storey_m, int storeys = 2) {
  maps::PlaneMap map = make_box_room();
  for (int s = 1; s < storeys; ++s) add_room_storey(map, s * storey_m, {10, 6}, true);
  return map;
}

/// Nearest positive hit of the ray origin + t·direction with any polygon, or +∞.
inline double cast_ray(const maps::PlaneMap& map, const Eigen::Vector3d& origin,
                       const Eigen::Vector3d& direction) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& polygon : map.polygons) {
    const double denominator = polygon.plane.normal.dot(direction);
    if (std::abs(denominator) < 1e-12) continue;
    const double t = -polygon.plane.signed_distance(origin) / denominator;
    if (!(t > 1e-9) || t >= best) continue;
    if (polygon.contains_uv(polygon.frame.project(origin + t * direction))) best = t;
  }
  return best;
}

struct SyntheticScanOptions {
  double azimuth_step_rad = 1.0 * M_PI / 180.0;
  double azimuth_offset_rad = 0.0;  ///< of the first firing: real rotations start anywhere
  double range_sigma_m = 0.0;
  double max_range_m = 100.0;
  double start_time_s = 0.0;
  double rotation_period_s = 0.1;
};

/// A VLP-16 scan while the sensor moves from T_map_start to T_map_end over one rotation (pose of
/// each firing interpolated at constant velocity): every ring at every azimuth step, ranges from
/// cast_ray() plus Gaussian noise; firing times spread linearly over the rotation.
inline sensor::Scan make_scan(const maps::PlaneMap& map, const localizer::Pose3& T_map_start,
                              const localizer::Pose3& T_map_end,
                              const SyntheticScanOptions& options, std::mt19937_64& rng) {
  const auto calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  sensor::Scan scan;
  scan.start_time_s = options.start_time_s;
  scan.end_time_s = options.start_time_s + options.rotation_period_s;
  scan.rings.resize(calibration.lasers.size());
  std::normal_distribution<double> noise(0.0, 1.0);
  const int steps = static_cast<int>(std::round(2.0 * M_PI / options.azimuth_step_rad));
  for (const auto& laser : calibration.lasers) {
    sensor::RingScan& ring = scan.rings[laser.ring];
    ring.ring = laser.ring;
    ring.elevation_rad = laser.elevation_rad;
    ring.vertical_offset_m = laser.vertical_offset_m;
    for (int s = 0; s < steps; ++s) {
      const double azimuth = options.azimuth_offset_rad + s * options.azimuth_step_rad;
      const localizer::Pose3 T_map_sensor =
          localizer::interpolate_pose(T_map_start, T_map_end, static_cast<double>(s) / steps);
      const Eigen::Vector3d apex_map =
          T_map_sensor * Eigen::Vector3d(0, 0, laser.vertical_offset_m);
      const Eigen::Vector3d d_sensor(std::cos(laser.elevation_rad) * std::cos(azimuth),
                                     std::cos(laser.elevation_rad) * std::sin(azimuth),
                                     std::sin(laser.elevation_rad));
      const double range = cast_ray(map, apex_map, T_map_sensor.linear() * d_sensor);
      sensor::Return ret;
      ret.azimuth_rad = azimuth;
      ret.time_s = options.start_time_s + options.rotation_period_s * s / steps;
      if (range < options.max_range_m) {
        ret.range_m = range + options.range_sigma_m * noise(rng);
      } else {
        ret.status = sensor::ReturnStatus::NoReturn;
      }
      ring.returns.push_back(ret);
    }
  }
  return scan;
}

}  // namespace conicloc::test

namespace conicloc::test {

/// A scan from a sensor standing still at T_map_sensor.
inline sensor::Scan make_scan(const maps::PlaneMap& map, const localizer::Pose3& T_map_sensor,
                              const SyntheticScanOptions& options, std::mt19937_64& rng) {
  return make_scan(map, T_map_sensor, T_map_sensor, options, rng);
}

/// A scan from a sensor standing still at T_map_sensor, one firing every `azimuth_step_rad`,
/// ranges with Gaussian noise `range_sigma_m` drawn from a generator seeded with `seed`.
inline sensor::Scan make_scan(const maps::PlaneMap& map, const localizer::Pose3& T_map_sensor,
                              double azimuth_step_rad, double range_sigma_m, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  SyntheticScanOptions options;
  options.azimuth_step_rad = azimuth_step_rad;
  options.range_sigma_m = range_sigma_m;
  return make_scan(map, T_map_sensor, options, rng);
}

}  // namespace conicloc::test
