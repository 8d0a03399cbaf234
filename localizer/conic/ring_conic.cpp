#include "localizer/conic/ring_conic.hpp"

#include <cmath>
#include <numbers>

namespace conicloc::localizer {

double RingConic::range(double azimuth_rad) const {
  return E / denominator(std::cos(azimuth_rad), std::sin(azimuth_rad));
}

bool RingConic::hit(double azimuth_rad, double& range_m) const {
  const double den = denominator(std::cos(azimuth_rad), std::sin(azimuth_rad));
  // Same strict sign for E and the denominator: r in (0, ∞). Never divides by zero.
  if (!((E > 0.0 && den > 0.0) || (E < 0.0 && den < 0.0))) return false;
  range_m = E / den;
  return std::isfinite(range_m);
}

RingConic ring_conic(const RingGeometry& ring, const SensorPlane& plane) {
  const Eigen::Vector3d& n = plane.normal;
  return {n.x() * ring.cos_elevation, n.y() * ring.cos_elevation, n.z() * ring.sin_elevation,
          -(plane.offset + n.z() * ring.vertical_offset_m)};
}

bool AzimuthInterval::full() const {
  return end_rad - begin_rad >= 2.0 * std::numbers::pi;
}

AzimuthInterval visible_interval(const RingConic& conic) {
  constexpr double kPi = std::numbers::pi;
  if (conic.E == 0.0) return {0.0, 0.0};
  const double s = conic.E > 0.0 ? 1.0 : -1.0;
  // r > 0  ⇔  s·(A cos θ + B sin θ) > −s·C  ⇔  R cos(θ − ψ) > −s·C.
  const double radius = std::sqrt(conic.A * conic.A + conic.B * conic.B);
  const double threshold = -s * conic.C;
  if (threshold < -radius) return {0.0, 2.0 * kPi};  // every beam (includes R = 0, sC > 0)
  if (threshold >= radius) return {0.0, 0.0};        // no beam (includes R = 0, sC ≤ 0)
  const double psi = std::atan2(s * conic.B, s * conic.A);
  const double half_width = std::acos(threshold / radius);  // |threshold/R| < 1 here
  return {psi - half_width, psi + half_width};
}

}  // namespace conicloc::localizer
