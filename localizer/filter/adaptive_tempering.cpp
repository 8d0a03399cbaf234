#include "localizer/filter/adaptive_tempering.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace conicloc::localizer {

double conditional_ess(std::span<const double> normalised_log_weights,
                       std::span<const double> log_likelihoods, double exponent) {
  const std::size_t n = std::min(normalised_log_weights.size(), log_likelihoods.size());
  double best = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    if (std::isfinite(log_likelihoods[i])) best = std::max(best, log_likelihoods[i]);
  }
  if (!std::isfinite(best)) return 0.0;
  // G_i scaled by exp(−τ·max ℓ) so the largest is 1: CESS is invariant to that scale.
  double first = 0.0;
  double second = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(log_likelihoods[i])) continue;
    const double prior = std::exp(normalised_log_weights[i]);
    const double increment = std::exp(exponent * (log_likelihoods[i] - best));
    first += prior * increment;
    second += prior * increment * increment;
  }
  return second > 0.0 ? static_cast<double>(n) * first * first / second : 0.0;
}

double adaptive_tempering_exponent(std::span<const double> normalised_log_weights,
                                   std::span<const double> log_likelihoods, double max_exponent,
                                   double min_ess_fraction) {
  if (!(min_ess_fraction > 0.0) || !(max_exponent > 0.0)) return max_exponent;
  const double target =
      min_ess_fraction * conditional_ess(normalised_log_weights, log_likelihoods, 0.0);
  if (!(target > 0.0)) return max_exponent;  // nothing finite to weigh: τ does not matter
  if (conditional_ess(normalised_log_weights, log_likelihoods, max_exponent) >= target)
    return max_exponent;
  // CESS(0) ≥ target > CESS(τ_max): bisect, keeping CESS(lo) ≥ target. CESS does not grow with
  // τ: d log CESS / dτ = 2·(E_τ[ℓ] − E_2τ[ℓ]) ≤ 0, E_s the mean under weights ∝ W·exp(s·ℓ), which
  // rises with s (the mean of an exponential family grows with its natural parameter).
  double lo = 0.0;
  double hi = max_exponent;
  while (hi - lo > 1e-3 * max_exponent) {
    const double mid = 0.5 * (lo + hi);
    (conditional_ess(normalised_log_weights, log_likelihoods, mid) >= target ? lo : hi) = mid;
  }
  // lo = 0 only if CESS falls below the target within 1e-3·τ_max: take that smallest step rather
  // than ignore the scan.
  return std::max(lo, 1e-3 * max_exponent);
}

}  // namespace conicloc::localizer
