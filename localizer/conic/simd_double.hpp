#pragma once
// Two doubles computed as one (the GCC/Clang vector extension: an SSE2 register in the default
// x86-64 build, a NEON register on aarch64; every operation rounds each lane as the scalar one
// does), and e^(−x) over them, for the per-particle, per-beam loops of conic-beam.
//   e^(−x) = 2^k · e^r,  k = round(−x / ln 2),  r = −x − k ln 2 ∈ [−ln2/2, ln2/2]:
// k by adding and subtracting 1.5·2^52 (the FPU's round to nearest, no conversion), k ln 2 in two
// parts (Cody & Waite: ln 2 = L_hi + L_lo, L_hi with its low 21 bits zero, so k L_hi is exact
// for |k| < 2^21),
// e^r by a polynomial of degree 11: the Chebyshev fit of e^r on [−ln2/2, ln2/2] (computed with
// mpmath.chebyfit at 40 digits; 1.7·10⁻¹⁷ relative error with its coefficients rounded to
// double), 2^k written into the exponent field. Relative error below 5·10⁻¹⁶ for 0 ≤ x ≤ 708
// (test_simd_double).

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace conicloc::localizer {

using SimdDouble = double __attribute__((vector_size(16)));
/// A lane comparison's result: all bits set where true (the compiler's own type for it).
using SimdMask = decltype(SimdDouble{} < SimdDouble{});
/// The lanes' bits, for arithmetic on them (unsigned: wraps, never overflows).
using SimdBits = std::uint64_t __attribute__((vector_size(16)));
inline constexpr std::size_t kSimdLanes = 2;

inline SimdDouble simd_broadcast(double value) {
  return SimdDouble{} + value;
}

inline SimdDouble simd_load(const double* values) {
  SimdDouble v;
  std::memcpy(&v, values, sizeof v);
  return v;
}

inline void simd_store(double* out, SimdDouble values) {
  std::memcpy(out, &values, sizeof values);
}

/// The lanes where `mask` is set, 0 elsewhere.
inline SimdDouble simd_keep(SimdMask mask, SimdDouble values) {
  return std::bit_cast<SimdDouble>(std::bit_cast<SimdBits>(mask) & std::bit_cast<SimdBits>(values));
}

/// |values| per lane.
inline SimdDouble simd_abs(SimdDouble values) {
  return std::bit_cast<SimdDouble>(std::bit_cast<SimdBits>(values) & (~std::uint64_t{0} >> 1));
}

/// e^(−x) per lane: within 5·10⁻¹⁶ (relative) for 0 ≤ x ≤ 708; outside (∞, NaN too) some value,
/// with no trap, to be masked out.
inline SimdDouble simd_exp_negative(SimdDouble x) {
  const SimdDouble shift = simd_broadcast(0x1.8p52);
  const SimdDouble t = x * -1.4426950408889634074 + shift;  // −x / ln 2 + 1.5·2^52
  const SimdDouble k = t - shift;                           // round(−x / ln 2)
  const SimdDouble r = (-x - k * 6.93147180369123816490e-01) - k * 1.90821492927058770002e-10;
  // e^r ≈ Σ c_j r^j, j = 0..11, by Estrin's scheme: pairs, then pairs of pairs with r², r⁴, r⁸ — a
  // dependency chain of 5 steps instead of Horner's 11, so the loops' iterations overlap.
  const SimdDouble r2 = r * r, r4 = r2 * r2, r8 = r4 * r4;
  const SimdDouble p01 = 1.0 + r * 1.0, p23 = 0.5000000000000019 + r * 0.1666666666666668,
                   p45 = 0.0416666666664881 + r * 0.008333333333319601,
                   p67 = 0.0013888888952314775 + r * 0.00019841269890047113,
                   p89 = 2.4801485482328494e-05 + r * 2.755724091857897e-06,
                   p1011 = 2.763263963904103e-07 + r * 2.5110037605963777e-08;
  const SimdDouble p = (p01 + r2 * p23) + r4 * (p45 + r2 * p67) + r8 * (p89 + r2 * p1011);
  // t's low mantissa bits hold 2^51 + k; shifted by 52 with the exponent bias, only k + 1023
  // stays: the bits of 2^k.
  const SimdBits two_to_k = (std::bit_cast<SimdBits>(t) + 1023) << 52;
  return p * std::bit_cast<SimdDouble>(two_to_k);
}

}  // namespace conicloc::localizer
