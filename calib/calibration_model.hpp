#pragma once
// The measurement model that calibration fits: where a return lands in the map, given the laser's
// corrections, the sensor's mounting and the scan's planar pose.
//
// A return of laser k decoded with a calibration C₀ carries (θ, r) = (−α + ψ⁰_k, r_raw + d⁰_k).
// With corrections (Δφ, Δo, Δψ, Δd) the laser is (φ⁰+Δφ, o⁰+Δo, ψ⁰+Δψ, d⁰+Δd) and the return is
//   p_S = (0, 0, o⁰+Δo) + (r+Δd)·(cos φ cos(θ+Δψ), cos φ sin(θ+Δψ), sin φ),  φ = φ⁰+Δφ
// exactly the ray the decoder (io/velodyne_decoder) and the simulator (sim/vlp16_simulator) use.
// The sensor rides a carrier on a level floor: at the scan's reference time
//   T_map_sensor = C · M,  C = Trans(x, y, z_floor) · Rz(yaw),
//   M = Trans(0, 0, h) · Ry(pitch) · Rx(roll)
// with the mounting M (h, roll, pitch) shared by every scan and the carrier's pose C (x, y, yaw)
// per scan. A return fired at τ = t − t_ref (≤ 0, de-skew) is where the carrier had moved by
// its planar velocity (v_x, v_y, ω) and yaw acceleration α through the scan, also fitted per
// scan:
//   p_map = C · E(τ) · M · p_S,  E(τ) = (Rz(θ(τ)), Rz(θ̄(τ))·(v_x, v_y, 0)·τ),
//   θ(τ) = ω·τ + α·τ²/2,  θ̄(τ) = ω·τ/2 + α·τ²/6 (the mean heading over [τ, 0])
// (a constant speed: along the chord of the arc, with the arc's length; the chord's is shorter
// by (ω·τ)²/24, 20 µm at 1 m/s and 1 rad/s over a 0.1 s scan). The yaw acceleration is there
// because a carrier turning in place speeds its turn up and down at a few rad/s²: at 3 rad/s²
// the heading leaves a constant rate's line by 0.07–0.14° within one scan (5–10 mm on a wall
// 4 m off), which a constant-rate fit put into the lasers (FJK-Haus, noise-free capture with
// the planes held: elevations 0.0078° RMS off, 16σ for the near-level lasers). The localizer's
// motion from the scan before is only the start: its few-centimetre pose errors, held as the
// de-skew, held the elevations 0.04° off on noise-free captures. Against its plane
// a·x + b = 0: the range residual r − r̂ along the ray (range_residual below).

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <vector>

#include "maps/planar_polygon.hpp"
#include "sensor/laser_calibration.hpp"

namespace conicloc::calib {

/// Corrections to one laser, added to the decode calibration.
struct LaserCorrection {
  double elevation_rad = 0.0;      ///< Δφ
  double vertical_offset_m = 0.0;  ///< Δo
  double azimuth_rad = 0.0;        ///< Δψ
  double range_m = 0.0;            ///< Δd
};

/// The sensor on its carrier: height above the floor, roll and pitch.
struct Mounting {
  double height_m = 0.0;
  double roll_rad = 0.0;
  double pitch_rad = 0.0;
};

/// A scan's planar pose at its reference time, the floor height under it (held fixed) and the
/// carrier's velocity through the scan, in the carrier's frame.
struct ScanPose {
  double x_m = 0.0;
  double y_m = 0.0;
  double yaw_rad = 0.0;
  double floor_z_m = 0.0;
  double vx_mps = 0.0;                 ///< forward
  double vy_mps = 0.0;                 ///< left
  double yaw_rate_rps = 0.0;           ///< ω at the reference time
  double yaw_acceleration_rps2 = 0.0;  ///< α
};

/// Where a mapped surface really stands (plane adjustment): off its polygon's plane by
///   δ + s_u·u + s_v·v
/// along the normal at in-plane coordinates (u, v) from the polygon's centroid (frame e_u, e_v):
/// an offset and two small tilts. A surveyed wall stands centimetres off and out of plumb; held
/// fixed, those errors reach the elevations (a 2 cm error seen at 4 m is 0.3°).
struct PlaneCorrection {
  double offset_m = 0.0;  ///< δ
  double slope_u = 0.0;   ///< s_u, metres per metre along e_u
  double slope_v = 0.0;   ///< s_v, along e_v
};

/// One measured return, as decoded.
struct Return {
  int laser = 0;  ///< channel
  int scan = 0;   ///< index into the scan poses
  double azimuth_rad = 0.0;
  double range_m = 0.0;
  double time_s = 0.0;  ///< τ: firing time − the scan's reference time (its end, so τ ≤ 0)
};

/// Parameters per laser, mounting and scan, in the order of the solver's state vector.
constexpr int kLaserParameters = 4;  ///< Δφ, Δo, Δψ, Δd
constexpr int kMountParameters = 3;  ///< h, roll, pitch
constexpr int kScanParameters = 7;   ///< x, y, yaw, v_x, v_y, ω, α
constexpr int kPlaneParameters = 3;  ///< δ, s_u, s_v
/// What one return's ray depends on: its laser's, the mounting's and its scan's parameters.
constexpr int kRayParameters = kLaserParameters + kMountParameters + kScanParameters;
using RayGradient = Eigen::Matrix<double, kRayParameters, 1>;

/// The laser's ray point in the sensor frame (p_S above), `laser` being the decode calibration's.
Eigen::Vector3d sensor_point(const sensor::Laser& laser, const LaserCorrection& correction,
                             double azimuth_rad, double range_m);

/// T_map_sensor of a scan at its reference time, C·M.
Eigen::Isometry3d map_from_sensor(const Mounting& mounting, const ScanPose& pose);

/// A scan's pose at its end, `T_map_target`, and the carrier's velocity over the `interval_s`
/// before it from the pose then, `T_map_previous` (both T_map_sensor; their planar parts), such
/// that E(−interval) = C_target⁻¹·C_previous. A turn faster than kMaxStartYawRate or a speed above
/// kMaxStartSpeed (a relocalization between the two) starts the carrier at rest instead.
ScanPose scan_pose_between(const Eigen::Isometry3d& T_map_previous,
                           const Eigen::Isometry3d& T_map_target, double interval_s,
                           double floor_z_m);
constexpr double kMaxStartSpeed = 5.0;       ///< m/s
constexpr double kMaxStartYawRate = M_PI;  ///< rad/s

/// E(τ): the carrier's motion from the scan's reference time to `time_s`, in its frame.
Eigen::Isometry3d carrier_motion(const ScanPose& pose, double time_s);

/// T_map_sensor when a return fired at `time_s`: C·E(τ)·M.
Eigen::Isometry3d map_from_fire(const Mounting& mounting, const ScanPose& pose, double time_s);

/// p_map of a return.
Eigen::Vector3d map_point(const sensor::Laser& laser, const LaserCorrection& correction,
                          const Mounting& mounting, const ScanPose& pose, const Return& ret);

/// Signed distance of `point_map` from `polygon`'s plane moved by `correction`.
double corrected_distance(const maps::PlanarPolygon& polygon, const PlaneCorrection& correction,
                          const Eigen::Vector3d& point_map);

/// The gradient a of corrected_distance over the point: n − s_u·e_u − s_v·e_v.
Eigen::Vector3d corrected_normal(const maps::PlanarPolygon& polygon,
                                 const PlaneCorrection& correction);

/// Where the range noise is: along the ray. A return measured at range r from `origin_map`
/// through `point_map` (unit direction d) meets the corrected plane D(x) = a·x + b = 0 at
///   r̂ = −D(origin)/(a·d),   and   r − r̂ = D(point)/(a·d),
/// the range residual (D(point) the point-to-plane residual over the cosine of incidence). Its
/// derivatives over every parameter but r are those of −r̂, which do not depend on the measured
/// range. Differentiated as a point-to-plane residual instead, the Jacobian (∝ r) and the
/// residual (∝ the noise) share the noise, E[Jᵀe] ∝ σ² ≠ 0, and the fit is biased by O(σ²)
/// (3 cm of range noise widened the elevations by 0.02–0.15° on average, one sign in every seed).
double range_residual(const maps::PlanarPolygon& polygon, const PlaneCorrection& correction,
                      const Eigen::Vector3d& origin_map, const Eigen::Vector3d& point_map);

/// ∂(r − r̂)/∂(Δφ, Δo, Δψ, Δd, h, roll, pitch, x, y, yaw, v_x, v_y, ω, α) of a return against its
/// polygon moved by `plane` (range_residual above), analytically. With r̂ = −D(o)/(a·d) and
/// r = range + Δd,
///   ∂(r − r̂)/∂θ = ∂r/∂θ + a·∂p̂/∂θ / (a·d),
/// where p̂ = o + r̂·d is the predicted hit carried by the ray at r̂ held: the derivatives move
/// the model's hit, never the measured point, so none holds the range noise.
RayGradient range_residual_gradient(const sensor::Laser& laser, const LaserCorrection& correction,
                                    const Mounting& mounting, const ScanPose& pose,
                                    const Return& ret, const maps::PlanarPolygon& polygon,
                                    const PlaneCorrection& plane);

/// |a·d|: the cosine of the ray's incidence on the corrected plane, from its direction alone.
/// The solvers fit c·(r − r̂) with c held at each step: the size of the point-to-plane residual
/// (a survey error met at grazing incidence weighs as the survey error, not as the long range
/// error it makes) with the range residual's noise-free derivatives, so E[Jᵀe] = 0.
double incidence_cosine(const maps::PlanarPolygon& polygon, const PlaneCorrection& correction,
                        const Eigen::Vector3d& origin_map, const Eigen::Vector3d& point_map);

/// The laser's origin (0, 0, o⁰ + Δo) in the sensor frame: where its rays start.
Eigen::Vector3d laser_origin(const sensor::Laser& laser, const LaserCorrection& correction);

/// The in-plane coordinates (u, v) of `point_map` from `polygon`'s centroid: what the slopes of
/// its correction multiply (d corrected_distance / d(δ, s_u, s_v) = −(1, u, v)).
Eigen::Vector2d centroid_uv(const maps::PlanarPolygon& polygon, const Eigen::Vector3d& point_map);

/// The decode calibration with the corrections added (one per laser, channel order).
sensor::LaserCalibration corrected(const sensor::LaserCalibration& decode,
                                   const std::vector<LaserCorrection>& corrections);

}  // namespace conicloc::calib
