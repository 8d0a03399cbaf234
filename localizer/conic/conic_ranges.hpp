#pragma once
// The ranges of one conic at many azimuths: the per-particle, per-beam hot path of conic-beam.
//   r(θ) = 1 / (a cos θ + b sin θ + c),
// a conic of a ring on a plane in its ray form (ring_conic.hpp), where the inverse lies in
// (1/r_max, 1/r_min]; no return (+∞) elsewhere (the plane behind the beam, or out of range).
// Evaluated two azimuths at a time (simd_double.hpp); each lane rounds as the scalar form.

#include <cstddef>
#include <limits>

namespace conicloc::localizer {

/// r from 1/r, or no return (+∞) outside (min_inverse, max_inverse] (0 included: a gap).
inline double range_from_inverse(double inverse, double min_inverse, double max_inverse) {
  return (inverse > min_inverse && inverse <= max_inverse)
             ? 1.0 / inverse
             : std::numeric_limits<double>::infinity();
}

/// out[k] = r(θ_k) for k < n, from cos θ_k and sin θ_k; `min_inverse` = 1/r_max,
/// `max_inverse` = 1/r_min.
void conic_ranges(double a, double b, double c, const double* cos_azimuth,
                  const double* sin_azimuth, std::size_t n, double min_inverse, double max_inverse,
                  double* out);

}  // namespace conicloc::localizer
