#pragma once
// Uniform draws that give the same numbers on every platform. The standard fixes the output of
// std::mt19937_64 but not that of std::uniform_real_distribution / uniform_int_distribution, so
// generated buildings compute their draws from the engine's bits themselves.

#include <cmath>
#include <cstdint>
#include <random>

namespace conicloc::sim {

/// Uniform in [lo, hi), from the top 53 bits of one draw.
inline double draw_uniform(std::mt19937_64& rng, double lo, double hi) {
  const double unit = static_cast<double>(rng() >> 11) * 0x1.0p-53;
  return lo + (hi - lo) * unit;
}

/// Uniform integer in [lo, hi]. Precondition: lo <= hi; the modulo bias is below 2^-59 for the
/// small ranges used here.
inline int draw_int(std::mt19937_64& rng, int lo, int hi) {
  const auto span = static_cast<std::uint64_t>(hi - lo) + 1;
  return lo + static_cast<int>(rng() % span);
}

/// A length in [lo, hi] metres rounded to whole centimetres, so files hold short numbers.
inline double draw_length(std::mt19937_64& rng, double lo_m, double hi_m) {
  return std::round(draw_uniform(rng, lo_m, hi_m) * 100.0) / 100.0;
}

}  // namespace conicloc::sim
