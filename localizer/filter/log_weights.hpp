#pragma once
// Log-domain weight arithmetic: log-sum-exp normalisation and the effective sample size.
// Weights are kept as logarithms so that likelihoods of thousands of beams (log-likelihoods of
// −10⁴ and below) neither underflow nor lose their ranking.

#include <span>

namespace conicloc::localizer {

/// log Σ exp(v_i), computed as m + log Σ exp(v_i − m) with m = max v_i. Returns −∞ for an empty
/// span or when every value is −∞; +∞ if any value is +∞. NaN values are treated as −∞.
double log_sum_exp(std::span<const double> values);

/// Normalises log-weights in place so that Σ exp(w_i) = 1 and returns the log-normaliser
/// (the log-sum-exp before normalisation). When every weight is −∞ (or NaN) the weights become
/// uniform, −log N, and the return value is −∞: the caller decides what a collapse means.
double normalise_log_weights(std::span<double> log_weights);

/// Effective sample size 1 / Σ w_i² of normalised log-weights (Kong, Liu & Wong 1994), in [1, N];
/// 0 for an empty span.
double effective_sample_size(std::span<const double> normalised_log_weights);

}  // namespace conicloc::localizer
