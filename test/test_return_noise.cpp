#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "calib/return_noise.hpp"

namespace conicloc::calib {
namespace {

constexpr double kDeg = M_PI / 180.0;

// Returns met at incidence angles spread evenly over 0–84° (plane_association.hpp's limit),
// with range noise σ_r along the ray and a surface error σ_s across the surface (σ_s/c along the
// ray); a fraction of them replaced by returns anywhere within ±0.3 m (objects, wrong surfaces).
struct Residuals {
  std::vector<double> range_m;
  std::vector<double> cosine;
};

Residuals draw(double range_sigma_m, double surface_sigma_m, double outliers, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> angle(0.0, 84.0 * kDeg);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_real_distribution<double> anywhere(-0.3, 0.3);
  std::normal_distribution<double> gauss(0.0, 1.0);
  Residuals out;
  for (int i = 0; i < 40000; ++i) {
    const double c = std::cos(angle(rng));
    const double e = range_sigma_m * gauss(rng) + surface_sigma_m / c * gauss(rng);
    out.range_m.push_back(unit(rng) < outliers ? anywhere(rng) : e);
    out.cosine.push_back(c);
  }
  return out;
}

// 40,000 returns in 10 bins: each bin's σ from its MAD is within about 2% (1σ); the line through
// them, and so each σ, within 10% over the seeds.
constexpr double kRelative = 0.10;

TEST(ReturnNoise, RangeNoiseAndSurfaceErrorAreToldApartByTheIncidence) {
  for (const unsigned seed : {1u, 2u, 3u}) {
    const Residuals r = draw(0.03, 0.01, 0.0, seed);
    const ReturnNoise noise = fit_return_noise(r.range_m, r.cosine);
    EXPECT_NEAR(noise.range_sigma_m, 0.03, kRelative * 0.03) << seed;
    EXPECT_NEAR(noise.surface_sigma_m, 0.01, kRelative * 0.01) << seed;
    // A return met at 78° weighs as it should: q = 0.2·√(10⁻³/1.36·10⁻⁴) = 0.542.
    EXPECT_NEAR(noise.residual_scale(0.2), 0.542, 0.05 * 0.542) << seed;
  }
}

TEST(ReturnNoise, ReturnsOffTheSurfaceDoNotWidenIt) {
  // 5% of the returns anywhere within ±0.3 m: their variance (0.03 m²) is 20 times the noise's
  // at normal incidence; the bins' medians raise σ by about 5%.
  const Residuals r = draw(0.03, 0.01, 0.05, 4);
  const ReturnNoise noise = fit_return_noise(r.range_m, r.cosine);
  EXPECT_NEAR(noise.range_sigma_m, 0.03, kRelative * 0.03);
  EXPECT_NEAR(noise.surface_sigma_m, 0.01, 2 * kRelative * 0.01);
}

TEST(ReturnNoise, EachSourceAloneIsFoundAlone) {
  const Residuals surface = draw(0.0, 0.02, 0.0, 5);
  const ReturnNoise from_surface = fit_return_noise(surface.range_m, surface.cosine);
  EXPECT_NEAR(from_surface.surface_sigma_m, 0.02, kRelative * 0.02);
  // The intercept σ_r² is read beside σ_s²/c² ≥ σ_s²: a few % of it is the bins' spread.
  EXPECT_LT(from_surface.range_sigma_m, 0.3 * 0.02);
  EXPECT_NEAR(from_surface.residual_scale(0.2), 0.2, 0.05 * 0.2);  // the point-to-plane size

  const Residuals range = draw(0.03, 0.0, 0.0, 6);
  const ReturnNoise from_range = fit_return_noise(range.range_m, range.cosine);
  EXPECT_NEAR(from_range.range_sigma_m, 0.03, kRelative * 0.03);
  EXPECT_LT(from_range.surface_sigma_m, 0.1 * 0.03);
  EXPECT_NEAR(from_range.residual_scale(0.2), 1.0, 0.05);  // the range residual, unscaled
}

TEST(ReturnNoise, TheScaleIsTheResidualsStandardDeviationAtNormalIncidenceOverItsOwn) {
  // q(c) = √(V(1)/V(c)), V(c) = σ_r² + σ_s²/c².
  const ReturnNoise both{0.02, 0.02};
  EXPECT_DOUBLE_EQ(both.residual_scale(1.0), 1.0);
  EXPECT_DOUBLE_EQ(both.residual_scale(0.5), std::sqrt((0.0004 + 0.0004) / (0.0004 + 0.0016)));
  EXPECT_DOUBLE_EQ(ReturnNoise{}.residual_scale(0.3), 0.3);  // unknown: c, surface error alone
  EXPECT_DOUBLE_EQ((ReturnNoise{0.0, 0.01}.residual_scale(0.3)), 0.3);
  EXPECT_DOUBLE_EQ((ReturnNoise{0.01, 0.0}.residual_scale(0.3)), 1.0);
}

TEST(ReturnNoise, TooFewReturnsLeaveItUnknownAndMismatchedInputsThrow) {
  const std::vector<double> residuals(100, 0.01), cosines(100, 0.5);
  const ReturnNoise noise = fit_return_noise(residuals, cosines);
  EXPECT_EQ(noise.range_sigma_m, 0.0);
  EXPECT_EQ(noise.surface_sigma_m, 0.0);
  const std::vector<double> short_cosines(99, 0.5);
  EXPECT_THROW(fit_return_noise(residuals, short_cosines), std::invalid_argument);
  std::vector<double> grazing(100, 0.5);
  grazing[42] = 0.0;  // a ray along its surface: no incidence to weigh by
  EXPECT_THROW(fit_return_noise(residuals, grazing), std::invalid_argument);
  EXPECT_EQ(ReturnNoise{0.01}.residual_scale(0.0), 0.0);
  ReturnNoiseConfig one_bin;
  one_bin.bins = 1;
  const Residuals r = draw(0.03, 0.01, 0.0, 1);
  EXPECT_EQ(fit_return_noise(r.range_m, r.cosine, one_bin).range_sigma_m, 0.0);
}

}  // namespace
}  // namespace conicloc::calib
