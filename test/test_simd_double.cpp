// The two-lane kernels of conic-beam's hot path against their scalar forms: e^(−x) within a few
// ulp of libm's over its whole domain, and the conic's ranges bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "localizer/conic/conic_ranges.hpp"
#include "localizer/conic/simd_double.hpp"

namespace cl = conicloc::localizer;

TEST(SimdDouble, ExpNegativeMatchesLibmOverItsDomain) {
  double worst = 0.0;
  for (double x = 0.0; x <= 708.0; x += 0.0137) {
    for (const double lane : {x, x * (1.0 + 1e-9)}) {
      const cl::SimdDouble e = cl::simd_exp_negative(cl::SimdDouble{lane, 708.0 - lane});
      worst = std::max(worst, std::abs(e[0] - std::exp(-lane)) / std::exp(-lane));
      worst = std::max(worst, std::abs(e[1] - std::exp(lane - 708.0)) / std::exp(lane - 708.0));
    }
  }
  EXPECT_LT(worst, 5e-16);
  // The ends and the points where k = round(x / ln 2) changes.
  for (const double x : {0.0, 708.0, 0.5 * M_LN2, 1.5 * M_LN2, 100.5 * M_LN2}) {
    const double e = cl::simd_exp_negative(cl::simd_broadcast(x))[0];
    EXPECT_NEAR(e, std::exp(-x), 5e-16 * std::exp(-x)) << x;
  }
  EXPECT_EQ(cl::simd_exp_negative(cl::simd_broadcast(0.0))[0], 1.0);
}

TEST(SimdDouble, ConicRangesEqualTheScalarFormBitForBit) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * M_PI), coefficient(-0.5, 0.5);
  const double lo = 1.0 / 100.0, hi = 1.0 / 0.3;
  for (const std::size_t n : {0u, 1u, 2u, 7u, 64u}) {  // odd counts: the scalar tail
    std::vector<double> cos_az, sin_az;
    for (std::size_t k = 0; k < n; ++k) {
      const double theta = angle(rng);
      cos_az.push_back(std::cos(theta));
      sin_az.push_back(std::sin(theta));
    }
    // In range, behind the beam (negative inverse) and out of range (too near, too far).
    for (const double c : {0.3, -0.2, 5.0, 0.001}) {
      const double a = coefficient(rng), b = coefficient(rng);
      std::vector<double> out(n, 0.0);
      cl::conic_ranges(a, b, c, cos_az.data(), sin_az.data(), n, lo, hi, out.data());
      for (std::size_t k = 0; k < n; ++k) {
        const double inverse = a * cos_az[k] + b * sin_az[k] + c;
        const double expected =
            inverse > lo && inverse <= hi ? 1.0 / inverse : std::numeric_limits<double>::infinity();
        EXPECT_EQ(out[k], expected) << "n " << n << ", c " << c << ", k " << k;
      }
    }
  }
}

TEST(SimdDouble, AbsAndKeep) {
  EXPECT_EQ(cl::simd_abs(cl::SimdDouble{-2.5, 0.0})[0], 2.5);
  const cl::SimdDouble kept =
      cl::simd_keep(cl::SimdDouble{1.0, 3.0} < 2.0, cl::SimdDouble{7.0, 9.0});
  EXPECT_EQ(kept[0], 7.0);
  EXPECT_EQ(kept[1], 0.0);
}
