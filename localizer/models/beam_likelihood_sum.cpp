#include "localizer/models/beam_likelihood_sum.hpp"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>

#include "localizer/conic/simd_double.hpp"

namespace conicloc::localizer {

BeamLikelihoodSum::BeamLikelihoodSum(const BeamMixtureConfig& config, const RangeNoise& noise,
                                     double max_range_m)
    : mixture_(config, noise, max_range_m),
      hit_scale_(config.hit_weight / (std::sqrt(2.0 * M_PI) * noise.sigma_m)),
      log_hit_scale_(std::log(hit_scale_)),
      log_random_density_(std::log(config.random_weight / max_range_m)),
      inverse_two_variance_(0.5 / (noise.sigma_m * noise.sigma_m)),
      random_density_(config.random_weight / max_range_m),
      gate_m_(noise.inlier_gate_m()),
      hit_cutoff_(std::numeric_limits<double>::infinity()) {
  const double highest =
      hit_scale_ + config.short_weight * config.short_rate_per_m + random_density_;
  if (!(random_density_ > 0.0) || !std::isfinite(highest) || !(highest > 0.0)) {
    chunk_ = 0;  // no floor: a density may underflow to 0
    return;
  }
  // Beyond this x the hit density is below 2⁻⁶⁰ of the smallest floor (as BeamMixture).
  hit_cutoff_ = std::log(hit_scale_ / random_density_) + 42.0;
  if (!(hit_cutoff_ <= 708.0)) {
    chunk_ = 0;  // a floor so small that e^(−x) is needed beyond simd_exp_negative's domain
    return;
  }
  // |log p| ≤ bound per beam: a product of k beams stays within e^±(k·bound); keep k·bound ≤ 600
  // (doubles reach e^±708).
  const double bound =
      std::max({std::abs(std::log(random_density_)), std::abs(std::log(highest)), 1.0});
  chunk_ = static_cast<std::size_t>(std::clamp(std::floor(600.0 / bound), 1.0, 64.0));
}

double BeamLikelihoodSum::sum(std::span<const double> measured_m,
                              std::span<const double> predicted_m,
                              std::span<const double> short_densities, std::size_t& inliers) const {
  assert(measured_m.size() == predicted_m.size() && measured_m.size() == short_densities.size());
  const std::size_t n = measured_m.size();
  inliers = 0;
  double log_sum = 0.0;
  if (chunk_ == 0) {
    for (std::size_t i = 0; i < n; ++i) {
      bool inlier = false;
      log_sum += mixture_.log_likelihood(measured_m[i], predicted_m[i],
                                         mixture_.floor_from_short(short_densities[i]), inlier);
      inliers += inlier ? 1 : 0;
    }
    return log_sum;
  }
  // p = H e^(−x) + F, x = (z − ẑ)²/2σ², F the floor density (with the short-reading term when
  // z < ẑ); ẑ = +∞ (no surface, x = ∞) and a NaN residual (x NaN, F without short readings) fail
  // x ≤ cutoff and leave the floor, as in BeamMixture::log_likelihood. Two beams at a time
  // (simd_double.hpp); each lane multiplies at most `chunk` beams before its log.
  const std::size_t packed = n - n % kSimdLanes;
  SimdMask inlier_count{};
  for (std::size_t first = 0; first < packed; first += chunk_ * kSimdLanes) {
    const std::size_t last = std::min(packed, first + chunk_ * kSimdLanes);
    SimdDouble product = simd_broadcast(1.0);
    for (std::size_t i = first; i < last; i += kSimdLanes) {
      const SimdDouble residual = simd_load(&measured_m[i]) - simd_load(&predicted_m[i]);
      const SimdDouble floor_density =
          random_density_ + simd_keep(residual < 0.0, simd_load(&short_densities[i]));
      const SimdDouble x = residual * residual * inverse_two_variance_;
      // e^(−x) of every lane, kept where x ≤ cutoff (elsewhere, ∞ and NaN included, it is outside
      // the domain of simd_exp_negative and left out).
      product *= simd_keep(x <= hit_cutoff_, hit_scale_ * simd_exp_negative(x)) + floor_density;
      inlier_count -= simd_abs(residual) <= gate_m_;  // a set mask is −1
    }
    log_sum += std::log(product[0]) + std::log(product[1]);
  }
  inliers = static_cast<std::size_t>(inlier_count[0] + inlier_count[1]);
  double product = 1.0;
  for (std::size_t i = packed; i < n; ++i) {  // fewer than a packet
    const double residual = measured_m[i] - predicted_m[i];
    const double floor_density =
        residual < 0.0 ? short_densities[i] + random_density_ : random_density_;
    const double x = residual * residual * inverse_two_variance_;
    inliers += std::abs(residual) <= gate_m_ ? 1 : 0;
    product *= x <= hit_cutoff_ ? hit_scale_ * std::exp(-x) + floor_density : floor_density;
  }
  log_sum += std::log(product);
  return log_sum;
}

double BeamLikelihoodSum::weighted_max_sum(std::span<const double> measured_m,
                                           std::span<const double> predicted_m,
                                           std::span<const double> weights,
                                           std::span<const double> log_short_floors,
                                           std::size_t& inliers) const {
  assert(weights.size() == measured_m.size());
  return max_form(measured_m, predicted_m, weights, log_short_floors, inliers);
}

double BeamLikelihoodSum::max_sum(std::span<const double> measured_m,
                                  std::span<const double> predicted_m,
                                  std::span<const double> log_short_floors,
                                  std::size_t& inliers) const {
  return max_form(measured_m, predicted_m, {}, log_short_floors, inliers);
}

double BeamLikelihoodSum::max_form(std::span<const double> measured_m,
                                   std::span<const double> predicted_m,
                                   std::span<const double> weights,
                                   std::span<const double> log_short_floors,
                                   std::size_t& inliers) const {
  assert(measured_m.size() == predicted_m.size() && measured_m.size() == log_short_floors.size());
  const bool weighted = !weights.empty();
  const std::size_t n = measured_m.size();
  // ẑ = +∞ (nothing predicted) makes the residual −∞ and log_hit −∞: the short floor, as in
  // log_likelihood(); a NaN residual is not < 0 and its NaN log_hit never wins: the long floor.
  const double log_random = log_random_density_;
  const std::size_t packed = n - n % kSimdLanes;
  SimdDouble total{};
  SimdMask inlier_count{};
  for (std::size_t i = 0; i < packed; i += kSimdLanes) {
    const SimdDouble residual = simd_load(&measured_m[i]) - simd_load(&predicted_m[i]);
    const SimdMask is_short = residual < 0.0;
    const SimdDouble log_floor = simd_keep(is_short, simd_load(&log_short_floors[i])) +
                                 simd_keep(~is_short, simd_broadcast(log_random));
    const SimdDouble log_hit = log_hit_scale_ - residual * residual * inverse_two_variance_;
    const SimdMask hit_wins = log_hit > log_floor;
    // Of each sum's two terms one is 0: a −∞ or NaN left out stays out.
    const SimdDouble best = simd_keep(hit_wins, log_hit) + simd_keep(~hit_wins, log_floor);
    total += weighted ? simd_load(&weights[i]) * best : best;
    inlier_count -= simd_abs(residual) <= gate_m_;  // a set mask is −1
  }
  double log_sum = total[0] + total[1];
  inliers = static_cast<std::size_t>(inlier_count[0] + inlier_count[1]);
  for (std::size_t i = packed; i < n; ++i) {  // fewer than a packet
    const double residual = measured_m[i] - predicted_m[i];
    const double log_floor = residual < 0.0 ? log_short_floors[i] : log_random;
    const double log_hit = log_hit_scale_ - residual * residual * inverse_two_variance_;
    inliers += std::abs(residual) <= gate_m_ ? 1 : 0;
    log_sum += (weighted ? weights[i] : 1.0) * (log_hit > log_floor ? log_hit : log_floor);
  }
  return log_sum;
}

}  // namespace conicloc::localizer
