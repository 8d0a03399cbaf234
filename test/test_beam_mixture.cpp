// The robust beam mixture (also the conic-segment model's per-segment term): its log-sum-exp
// form agrees with the log of the mixture density, and the inlier gate is |residual| ≤ kσ.
#include <gtest/gtest.h>

#include <cmath>

#include "localizer/models/beam_mixture.hpp"

namespace cl = conicloc::localizer;

TEST(BeamMixture, LogLikelihoodIsTheLogOfTheMixtureDensity) {
  const cl::BeamMixtureConfig config;
  const cl::RangeNoise noise;
  const cl::BeamMixture mixture(config, noise, conicloc::sensor::kMaxRange_m);
  for (const double measured : {0.7, 3.0, 12.5}) {
    const cl::BeamFloor floor = mixture.floor(measured);
    for (double predicted = 0.5; predicted < 15.0; predicted += 0.0137) {
      bool inlier = false;
      const double value = mixture.log_likelihood(measured, predicted, floor, inlier);
      const double residual = measured - predicted;
      const double hit = config.hit_weight / (std::sqrt(2.0 * M_PI) * noise.sigma_m) *
                         std::exp(-0.5 * residual * residual / (noise.sigma_m * noise.sigma_m));
      const double rest = std::exp(residual < 0.0 ? floor.with_short : floor.without_short);
      EXPECT_NEAR(value, std::log(hit + rest), 1e-12 * std::max(1.0, std::abs(value)));
      EXPECT_EQ(inlier, std::abs(residual) <= noise.inlier_sigmas * noise.sigma_m);
    }
  }
}
