#include "localizer/conic/conic_ranges.hpp"

#include <limits>

#include "localizer/conic/simd_double.hpp"

namespace conicloc::localizer {

void conic_ranges(double a, double b, double c, const double* cos_azimuth,
                  const double* sin_azimuth, std::size_t n, double min_inverse, double max_inverse,
                  double* out) {
  constexpr double kNoReturn = std::numeric_limits<double>::infinity();
  std::size_t k = 0;
  for (; k + kSimdLanes <= n; k += kSimdLanes) {
    // (a cos θ + b sin θ) + c, in the scalar form's order: the same rounding in every lane.
    const SimdDouble inverse = a * simd_load(cos_azimuth + k) + b * simd_load(sin_azimuth + k) + c;
    const SimdMask in_range = (inverse > min_inverse) & (inverse <= max_inverse);
    simd_store(out + k, in_range ? 1.0 / inverse : simd_broadcast(kNoReturn));
  }
  for (; k < n; ++k) {
    out[k] =
        range_from_inverse(a * cos_azimuth[k] + b * sin_azimuth[k] + c, min_inverse, max_inverse);
  }
}

}  // namespace conicloc::localizer
