#include "localizer/conic/projective_conic.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

namespace conicloc::localizer {

const char* conic_type_name(ConicType type) {
  switch (type) {
    case ConicType::Ellipse:
      return "ellipse";
    case ConicType::Parabola:
      return "parabola";
    case ConicType::Hyperbola:
      return "hyperbola";
    case ConicType::Degenerate:
      return "degenerate";
  }
  return "degenerate";
}

double ProjectiveConic::evaluate(double u, double v) const {
  const Eigen::Vector3d w(u, v, 1.0);
  return w.dot(C * w);
}

double conic_eccentricity(const RingGeometry& ring, const Eigen::Vector3d& normal_sensor) {
  const double horizontal = std::hypot(normal_sensor.x(), normal_sensor.y());
  if (horizontal == 0.0) return 0.0;  // level plane: a circle (or nothing)
  const double sin_abs = std::abs(ring.sin_elevation);
  if (sin_abs == 0.0) return std::numeric_limits<double>::infinity();  // the "cone" is a plane
  return horizontal / sin_abs;
}

ProjectiveConic projective_conic(const RingGeometry& ring, const SensorPlane& plane,
                                 double parabola_tolerance, double degenerate_tolerance_m) {
  const Eigen::Vector3d n = plane.normal.normalized();
  const RingConic ray = ring_conic(ring, plane);
  ProjectiveConic conic;
  // Foot point of the apex on the plane, relative to the apex: −(n·apex + D)·n = E·n.
  const Eigen::Vector3d p0 = ray.E * n;
  // In-plane basis: e_u horizontal when the plane is not level (along a wall), else along x.
  const Eigen::Vector3d along = Eigen::Vector3d::UnitZ().cross(n);
  conic.e_u = along.norm() > 1e-9 ? along.normalized()
                                  : (Eigen::Vector3d::UnitX() - n.x() * n).normalized();
  conic.e_v = n.cross(conic.e_u);
  conic.foot_point = ring.apex() + p0;
  conic.H.col(0) = conic.e_u;
  conic.H.col(1) = conic.e_v;
  conic.H.col(2) = p0;
  const double s2 = ring.sin_elevation * ring.sin_elevation;
  const double c2 = ring.cos_elevation * ring.cos_elevation;
  const Eigen::Vector3d q(s2, s2, -c2);  // Q_k = diag(sin²φ, sin²φ, −cos²φ)
  conic.C = conic.H.transpose() * q.asDiagonal() * conic.H;
  conic.eccentricity = conic_eccentricity(ring, n);
  // det C = det(H)² det Q = E² · sin⁴φ · (−cos²φ): zero exactly in these cases.
  if (std::abs(ray.E) <= degenerate_tolerance_m || s2 == 0.0 || c2 == 0.0) {
    conic.type = ConicType::Degenerate;
  } else if (std::abs(conic.eccentricity - 1.0) <= parabola_tolerance) {
    conic.type = ConicType::Parabola;
  } else {
    conic.type = conic.eccentricity < 1.0 ? ConicType::Ellipse : ConicType::Hyperbola;
  }
  return conic;
}

}  // namespace conicloc::localizer
