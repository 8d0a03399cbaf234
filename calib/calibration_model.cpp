#include "calib/calibration_model.hpp"

#include <array>
#include <cmath>

#include "localizer/conic/pose.hpp"

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

namespace {

// C = Trans(x, y, z_floor)·Rz(yaw) and M = Trans(0, 0, h)·Ry(pitch)·Rx(roll) (header).
Eigen::Isometry3d map_from_carrier(const ScanPose& pose) {
  Eigen::Isometry3d C = Eigen::Isometry3d::Identity();
  C.translation() = Eigen::Vector3d(pose.x_m, pose.y_m, pose.floor_z_m);
  C.linear() = Eigen::AngleAxisd(pose.yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return C;
}

Eigen::Isometry3d carrier_from_sensor(const Mounting& mounting) {
  Eigen::Isometry3d M = Eigen::Isometry3d::Identity();
  M.translation() = Eigen::Vector3d(0.0, 0.0, mounting.height_m);
  M.linear() = (Eigen::AngleAxisd(mounting.pitch_rad, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(mounting.roll_rad, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  return M;
}

}  // namespace

Eigen::Isometry3d map_from_sensor(const Mounting& mounting, const ScanPose& pose) {
  return map_from_carrier(pose) * carrier_from_sensor(mounting);
}

ScanPose scan_pose_between(const Eigen::Isometry3d& T_map_previous,
                           const Eigen::Isometry3d& T_map_target, double interval_s,
                           double floor_z_m) {
  ScanPose pose;
  const Eigen::Vector3d t = T_map_target.translation();
  pose.x_m = t.x();
  pose.y_m = t.y();
  pose.yaw_rad = localizer::yaw_of(T_map_target);
  pose.floor_z_m = floor_z_m;
  if (!(interval_s > 0.0)) return pose;
  // E(−I): rotation Rz(−ω·I) = Rz(yaw_prev − yaw), translation −Rz(−ω·I/2)·(v_x, v_y)·I =
  // Rz(−yaw)·(t_prev − t), so (v_x, v_y) = Rz(ω·I/2 − yaw)·(t − t_prev)/I.
  const double turn =
      std::remainder(pose.yaw_rad - localizer::yaw_of(T_map_previous), 2.0 * M_PI);
  const Eigen::Vector2d velocity =
      Eigen::Rotation2Dd(0.5 * turn - pose.yaw_rad) *
      (t - T_map_previous.translation()).head<2>() / interval_s;
  if (std::abs(turn) / interval_s > kMaxStartYawRate || velocity.norm() > kMaxStartSpeed) {
    return pose;
  }
  pose.yaw_rate_rps = turn / interval_s;
  pose.vx_mps = velocity.x();
  pose.vy_mps = velocity.y();
  return pose;
}

namespace {

// θ(τ) and θ̄(τ) of E(τ) (header).
double turn_at(const ScanPose& pose, double tau) {
  return pose.yaw_rate_rps * tau + 0.5 * pose.yaw_acceleration_rps2 * tau * tau;
}
double mean_heading(const ScanPose& pose, double tau) {
  return 0.5 * pose.yaw_rate_rps * tau + pose.yaw_acceleration_rps2 * tau * tau / 6.0;
}

}  // namespace

Eigen::Isometry3d carrier_motion(const ScanPose& pose, double time_s) {
  Eigen::Isometry3d E = Eigen::Isometry3d::Identity();
  E.linear() =
      Eigen::AngleAxisd(turn_at(pose, time_s), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  E.translation() = Eigen::AngleAxisd(mean_heading(pose, time_s), Eigen::Vector3d::UnitZ()) *
                    Eigen::Vector3d(pose.vx_mps * time_s, pose.vy_mps * time_s, 0.0);
  return E;
}

Eigen::Isometry3d map_from_fire(const Mounting& mounting, const ScanPose& pose, double time_s) {
  return map_from_carrier(pose) * carrier_motion(pose, time_s) * carrier_from_sensor(mounting);
}

Eigen::Vector3d map_point(const sensor::Laser& laser, const LaserCorrection& correction,
                          const Mounting& mounting, const ScanPose& pose, const Return& ret) {
  return map_from_fire(mounting, pose, ret.time_s) *
         sensor_point(laser, correction, ret.azimuth_rad, ret.range_m);
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
  return std::abs(corrected_normal(polygon, correction).dot((point_map - origin_map).normalized()));
}

RayGradient range_residual_gradient(const sensor::Laser& laser, const LaserCorrection& correction,
                                    const Mounting& mounting, const ScanPose& pose,
                                    const Return& ret, const maps::PlanarPolygon& polygon,
                                    const PlaneCorrection& plane) {
  const double phi = laser.elevation_rad + correction.elevation_rad;
  const double psi = ret.azimuth_rad + correction.azimuth_rad;
  // The unit ray u(φ, ψ) in the sensor frame and its derivatives.
  const Eigen::Vector3d u(std::cos(phi) * std::cos(psi), std::cos(phi) * std::sin(psi),
                          std::sin(phi));
  const Eigen::Vector3d du_dphi(-std::sin(phi) * std::cos(psi), -std::sin(phi) * std::sin(psi),
                                std::cos(phi));
  const Eigen::Vector3d du_dpsi(-std::cos(phi) * std::sin(psi), std::cos(phi) * std::cos(psi), 0.0);
  const Eigen::Vector3d origin_s = laser_origin(laser, correction);

  const Eigen::Isometry3d C = map_from_carrier(pose);
  const Eigen::Isometry3d E = carrier_motion(pose, ret.time_s);
  const Eigen::Isometry3d M = carrier_from_sensor(mounting);
  const Eigen::Isometry3d T = C * E * M;
  const Eigen::Vector3d a = corrected_normal(polygon, plane);
  const Eigen::Vector3d origin = T * origin_s;
  const Eigen::Vector3d d = T.linear() * u;
  const double a_d = a.dot(d);
  // r̂ = −D(o)/(a·d), D(x) = corrected_distance (affine in x, gradient a).
  const double r_hat = -corrected_distance(polygon, plane, origin) / a_d;
  const Eigen::Vector3d hit_s = origin_s + r_hat * u;  // p̂ in the sensor frame
  const Eigen::Vector3d hit_fire = M * hit_s;          // ... in the carrier's frame at the firing
  const Eigen::Vector3d hit_map = C * (E * hit_fire);

  // ∂p̂ in the map frame, then ∂e = ∂r + a·∂p̂/(a·d).
  const Eigen::Matrix3d R_ce = C.linear() * E.linear();
  const Eigen::AngleAxisd Ry(mounting.pitch_rad, Eigen::Vector3d::UnitY());
  const Eigen::AngleAxisd Rx(mounting.roll_rad, Eigen::Vector3d::UnitX());
  const double tau = ret.time_s;
  const Eigen::Matrix3d R_mean =
      Eigen::AngleAxisd(mean_heading(pose, tau), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  std::array<Eigen::Vector3d, kRayParameters> moved;
  moved[0] = T.linear() * (r_hat * du_dphi);                            // Δφ
  moved[1] = T.linear() * z;                                            // Δo
  moved[2] = T.linear() * (r_hat * du_dpsi);                            // Δψ
  moved[3] = Eigen::Vector3d::Zero();                                   // Δd: r only
  moved[4] = z;                                                         // h
  moved[5] = T.linear() * Eigen::Vector3d::UnitX().cross(hit_s);        // roll
  moved[6] = R_ce * (Ry * Eigen::Vector3d::UnitY().cross(Rx * hit_s));  // pitch
  moved[7] = Eigen::Vector3d::UnitX();                                  // x
  moved[8] = Eigen::Vector3d::UnitY();                                  // y
  moved[9] = z.cross(hit_map - C.translation());                        // yaw
  moved[10] = C.linear() * (R_mean * Eigen::Vector3d(tau, 0.0, 0.0));   // v_x
  moved[11] = C.linear() * (R_mean * Eigen::Vector3d(0.0, tau, 0.0));   // v_y
  // ω turns the fired point by ∂θ/∂ω = τ and the chord by ∂θ̄/∂ω = τ/2; α by τ²/2 and τ²/6.
  const Eigen::Vector3d turned_point = z.cross(E.linear() * hit_fire);
  const Eigen::Vector3d turned_chord = z.cross(E.translation());
  moved[12] = C.linear() * (tau * turned_point + 0.5 * tau * turned_chord);                    // ω
  moved[13] = C.linear() * (0.5 * tau * tau * turned_point + tau * tau / 6.0 * turned_chord);  // α
  RayGradient gradient;
  for (int j = 0; j < kRayParameters; ++j) gradient(j) = a.dot(moved[j]) / a_d;
  gradient(3) += 1.0;
  return gradient;
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
