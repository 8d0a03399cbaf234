#pragma once
// The ray (polar) form of the conic ring k cuts from a plane (DESIGN.md "The conic sensor model"):
//   r_k(θ) = E / (A cos θ + B sin θ + C),
//   A = n_x cos φ_k,  B = n_y cos φ_k,  C = n_z sin φ_k,  E = −(D + n_z o_k),
// for the plane n·p + D = 0 in the sensor frame (|n| = 1). Valid where r > 0. Equivalently
// 1/r = a cos θ + b sin θ + c with (a, b, c) = (A, B, C)/E: linear in the unknowns.
// Every quantity is finite for every elevation (φ = 0 included) and every plane.

#include <Eigen/Core>

#include "localizer/conic/ring_geometry.hpp"

namespace conicloc::localizer {

/// A plane n·p + D = 0 given in the sensor frame: n_s = Rᵀn, D_s = D + n·t for T_map_sensor = (R,
/// t).
struct SensorPlane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double offset = 0.0;  ///< D_s, metres
};

/// The map plane (n, D) seen from T_map_sensor = (R, t): n_s = Rᵀn, D_s = D + n·t.
/// Inline: it runs per particle and landmark.
inline SensorPlane to_sensor_plane(const Eigen::Vector3d& normal_map, double offset_map,
                                   const Eigen::Matrix3d& R_map_sensor,
                                   const Eigen::Vector3d& t_map_sensor) {
  return {R_map_sensor.transpose() * normal_map, offset_map + normal_map.dot(t_map_sensor)};
}

struct RingConic {
  double A = 0.0, B = 0.0, C = 0.0, E = 0.0;

  /// A cos θ + B sin θ + C.
  double denominator(double cos_theta, double sin_theta) const {
    return A * cos_theta + B * sin_theta + C;
  }
  /// r(θ) = E / (A cos θ + B sin θ + C); ±∞ or NaN where the beam is parallel to the plane. A
  /// non-positive value means the beam does not reach the plane (it points away or lies in it).
  double range(double azimuth_rad) const;
  /// True when the beam at θ meets the plane at a range in (0, ∞); `range_m` is then set.
  bool hit(double azimuth_rad, double& range_m) const;
};

/// The ring's conic on `plane` (sensor frame).
RingConic ring_conic(const RingGeometry& ring, const SensorPlane& plane);

/// An azimuth interval [begin, end] in radians, begin ≤ end, end − begin ≤ 2π; `begin` may be
/// negative or `end` beyond 2π (the interval is taken modulo 2π).
struct AzimuthInterval {
  double begin_rad = 0.0;
  double end_rad = 0.0;
  bool empty() const { return !(end_rad > begin_rad); }
  bool full() const;  ///< covers the whole circle
};

/// Where the ring sees the unbounded plane at a positive range: the closed-form interval
/// θ ∈ ψ ± acos(−sC/R), ψ = atan2(sB, sA), R = hypot(A, B), s = sign(E) (so around atan2(B, A),
/// or the opposite direction when E < 0). Open at its ends (r → ∞ there). Empty when E = 0 (the
/// apex lies in the plane: no beam meets it at a positive range) or the plane is out of reach;
/// full when every beam of the ring meets the plane.
AzimuthInterval visible_interval(const RingConic& conic);

}  // namespace conicloc::localizer
