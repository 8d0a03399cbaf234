#include "calib/calibration_model.hpp"

#include <cmath>

namespace conicloc::calib {

Eigen::Vector3d sensor_point(const sensor::Laser& laser, const LaserCorrection& correction,
                             double azimuth_rad, double range_m) {
  const double elevation = laser.elevation_rad + correction.elevation_rad;
  const double azimuth = azimuth_rad + correction.azimuth_rad;
  const double range = range_m + correction.range_m;
  const double horizontal = range * std::cos(elevation);
  return {horizontal * std::cos(azimuth), horizontal * std::sin(azimuth),
          laser.vertical_offset_m + correction.vertical_offset_m + range * std::sin(elevation)};
}

Eigen::Isometry3d map_from_sensor(const Mounting& mounting, const ScanPose& pose) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(pose.x_m, pose.y_m, pose.floor_z_m + mounting.height_m);
  T.linear() = (Eigen::AngleAxisd(pose.yaw_rad, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(mounting.pitch_rad, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(mounting.roll_rad, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  return T;
}

Eigen::Vector3d map_point(const sensor::Laser& laser, const LaserCorrection& correction,
                          const Mounting& mounting, const ScanPose& pose, const Return& ret) {
  return map_from_sensor(mounting, pose) *
         (ret.T_ref_fire * sensor_point(laser, correction, ret.azimuth_rad, ret.range_m));
}

Eigen::Vector2d centroid_uv(const maps::PlanarPolygon& polygon, const Eigen::Vector3d& point_map) {
  const Eigen::Vector3d q = point_map - polygon.centroid;
  return {q.dot(polygon.frame.e_u), q.dot(polygon.frame.e_v)};
}

double corrected_distance(const maps::PlanarPolygon& polygon, const PlaneCorrection& correction,
                          const Eigen::Vector3d& point_map) {
  const Eigen::Vector2d uv = centroid_uv(polygon, point_map);
  return polygon.plane.signed_distance(point_map) - correction.offset_m -
         correction.slope_u * uv.x() - correction.slope_v * uv.y();
}

Eigen::Vector3d corrected_normal(const maps::PlanarPolygon& polygon,
                                 const PlaneCorrection& correction) {
  return polygon.plane.normal - correction.slope_u * polygon.frame.e_u -
         correction.slope_v * polygon.frame.e_v;
}

double range_residual(const maps::PlanarPolygon& polygon, const PlaneCorrection& correction,
                      const Eigen::Vector3d& origin_map, const Eigen::Vector3d& point_map) {
  const Eigen::Vector3d direction = (point_map - origin_map).normalized();
  return corrected_distance(polygon, correction, point_map) /
         corrected_normal(polygon, correction).dot(direction);
}

double incidence_cosine(const maps::PlanarPolygon& polygon, const PlaneCorrection& correction,
                        const Eigen::Vector3d& origin_map, const Eigen::Vector3d& point_map) {
  return std::abs(
      corrected_normal(polygon, correction).dot((point_map - origin_map).normalized()));
}

Eigen::Vector3d laser_origin(const sensor::Laser& laser, const LaserCorrection& correction) {
  return {0.0, 0.0, laser.vertical_offset_m + correction.vertical_offset_m};
}

sensor::LaserCalibration corrected(const sensor::LaserCalibration& decode,
                                   const std::vector<LaserCorrection>& corrections) {
  sensor::LaserCalibration out = decode;
  for (std::size_t k = 0; k < out.lasers.size() && k < corrections.size(); ++k) {
    out.lasers[k].elevation_rad += corrections[k].elevation_rad;
    out.lasers[k].vertical_offset_m += corrections[k].vertical_offset_m;
    out.lasers[k].azimuth_offset_rad += corrections[k].azimuth_rad;
    out.lasers[k].range_offset_m += corrections[k].range_m;
  }
  return out;
}

}  // namespace conicloc::calib
