#include "localizer/filter/log_weights.hpp"

#include <cmath>
#include <limits>

namespace conicloc::localizer {

namespace {
constexpr double kMinusInfinity = -std::numeric_limits<double>::infinity();

double finite_or_minus_infinity(double value) {
  return std::isnan(value) ? kMinusInfinity : value;
}
}  // namespace

double log_sum_exp(std::span<const double> values) {
  double max_value = kMinusInfinity;
  for (const double v : values) max_value = std::max(max_value, finite_or_minus_infinity(v));
  if (!std::isfinite(max_value)) return max_value;  // −∞ (all −∞ or empty) or +∞
  double sum = 0.0;
  for (const double v : values) sum += std::exp(finite_or_minus_infinity(v) - max_value);
  return max_value + std::log(sum);
}

double normalise_log_weights(std::span<double> log_weights) {
  const double log_normaliser = log_sum_exp(log_weights);
  if (log_weights.empty()) return log_normaliser;
  if (!std::isfinite(log_normaliser)) {
    // All −∞ (or a +∞ we cannot rank): fall back to uniform weights; the collapse is reported
    // through the −∞ return value.
    const double uniform = -std::log(static_cast<double>(log_weights.size()));
    for (double& w : log_weights) w = uniform;
    return kMinusInfinity;
  }
  for (double& w : log_weights) w = finite_or_minus_infinity(w) - log_normaliser;
  return log_normaliser;
}

double effective_sample_size(std::span<const double> normalised_log_weights) {
  if (normalised_log_weights.empty()) return 0.0;
  double sum_squares = 0.0;
  for (const double w : normalised_log_weights) sum_squares += std::exp(2.0 * w);
  return sum_squares > 0.0 ? 1.0 / sum_squares : 0.0;
}

}  // namespace conicloc::localizer
