#pragma once
// Adaptive tempering of a scan likelihood (Jasra, Stephens, Doucet & Tsagaris 2011, "Inference
// for Lévy-driven stochastic volatility models via adaptive sequential Monte Carlo"; the
// conditional ESS of Zhou, Johansen & Aston 2016). A particle cloud spread over a whole building
// (global start, recovery) meets a scan whose likelihood differs by hundreds of nats between
// particles: weighted with the full exponent, one particle takes all the weight and the cloud
// collapses onto whichever hypothesis happened to be sampled closest to *some* fit — often the
// wrong one. Instead, each scan gets the largest exponent τ ≤ τ_max that keeps the conditional
// effective sample size of its incremental weights exp(τ·ℓ_i) above a fraction of N; the rest of
// the evidence comes from the following scans. A converged cloud, whose likelihoods are similar,
// keeps τ_max.

#include <span>

namespace conicloc::localizer {

/// Conditional ESS of the incremental weights G_i = exp(τ·ℓ_i) under normalised prior log-weights
/// w_i (Zhou, Johansen & Aston 2016, eq. 3.15):
///   CESS(τ) = N·(Σ W_i G_i)² / Σ W_i G_i²,  W_i = exp(w_i),
/// in [0, N]; it equals the ESS of the new weights when the prior weights are uniform. ℓ_i = −∞
/// (or NaN) contributes G_i = 0. 0 for empty input or when every ℓ_i is −∞.
double conditional_ess(std::span<const double> normalised_log_weights,
                       std::span<const double> log_likelihoods, double exponent);

/// The tempering exponent of one scan: τ_max when CESS(τ_max) ≥ target, else the largest τ in
/// (0, τ_max) with CESS(τ) ≥ target found by bisection (to a relative precision of 1e-3 of
/// τ_max), where target = `min_ess_fraction` · CESS(0⁺) (CESS(0⁺) = N times the prior mass of the
/// finite ℓ_i). `min_ess_fraction` ≤ 0 disables the adaptation (returns τ_max).
double adaptive_tempering_exponent(std::span<const double> normalised_log_weights,
                                   std::span<const double> log_likelihoods, double max_exponent,
                                   double min_ess_fraction);

}  // namespace conicloc::localizer
