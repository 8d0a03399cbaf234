#pragma once
// The projective form of a ring's conic (DESIGN.md, the paper's eq. 33 C_h = H⁻ᵀ C_u H⁻¹): with an
// orthonormal basis (e_u, e_v) of the plane and its foot point p0 relative to the ring's apex
// (0, 0, o_k), H = [e_u e_v p0] maps plane coordinates (u, v, 1) to apex-relative points; the
// ring's (double) cone is x² + y² − cot²φ z² = 0, scaled to Q_k = diag(sin²φ, sin²φ, −cos²φ) so
// φ → 0 stays finite; the conic in plane coordinates is C = Hᵀ Q_k H: (u, v, 1) C (u, v, 1)ᵀ = 0.
// Its eccentricity is e = |n_horizontal| / sin|φ|: ellipse (e < 1), parabola (e = 1), hyperbola.

#include <Eigen/Core>

#include "localizer/conic/ring_conic.hpp"
#include "localizer/conic/ring_geometry.hpp"

namespace conicloc::localizer {

enum class ConicType { Ellipse, Parabola, Hyperbola, Degenerate };

const char* conic_type_name(ConicType type);  ///< "ellipse", "parabola", "hyperbola", "degenerate"

struct ProjectiveConic {
  Eigen::Matrix3d H = Eigen::Matrix3d::Identity();  ///< [e_u e_v p0], apex-relative
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();      ///< Hᵀ Q_k H, symmetric
  Eigen::Vector3d e_u = Eigen::Vector3d::UnitX(), e_v = Eigen::Vector3d::UnitY();  ///< sensor frame
  Eigen::Vector3d foot_point = Eigen::Vector3d::Zero();  ///< p0 + apex: on the plane, sensor frame
  ConicType type = ConicType::Degenerate;
  double eccentricity = 0.0;  ///< +∞ for φ = 0 on a non-level plane

  /// The sensor-frame point of plane coordinates (u, v).
  Eigen::Vector3d point(double u, double v) const { return foot_point + u * e_u + v * e_v; }
  /// (u, v, 1) C (u, v, 1)ᵀ: zero on the conic.
  double evaluate(double u, double v) const;
};

/// Eccentricity of ring `ring`'s conic on a plane with sensor-frame unit normal n:
/// |n_horizontal| / sin|φ| (+∞ when φ = 0 and the plane is not level, 0 when the plane is level).
double conic_eccentricity(const RingGeometry& ring, const Eigen::Vector3d& normal_sensor);

/// The projective conic of `ring` on `plane` (sensor frame). Degenerate when the apex lies on the
/// plane (|E| ≤ degenerate_tolerance_m) or φ = 0 (the cone is a plane) or φ = ±90°; a parabola
/// when |e − 1| ≤ parabola_tolerance.
ProjectiveConic projective_conic(const RingGeometry& ring, const SensorPlane& plane,
                                 double parabola_tolerance = 1e-9,
                                 double degenerate_tolerance_m = 1e-12);

}  // namespace conicloc::localizer
