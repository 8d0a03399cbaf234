#pragma once
// The sum over a scan's beams of the robust mixture's log-likelihood (BeamMixture::log_likelihood)
// with one log per chunk of beams instead of one per beam: Σ log p_i = log Π p_i. Beams are taken
// two at a time (simd_double.hpp: its e^(−x) within 5·10⁻¹⁶), each lane multiplying at most
// `chunk` beams before its log. Every p_i lies in [w_rand/z_max, H + w_short·λ + w_rand/z_max]
// (H = w_hit/(√(2π)σ)), so the chunk is sized (≤ 64) for a product to stay far inside the double
// range: the same likelihood, rounded differently (relative error ~chunk ulp per chunk). The log
// was half of conic-beam's weighting time (one glibc log per beam and particle), e^(−x) the other.
// Without a uniform floor (w_rand = 0) a density can underflow to 0, and with one so small that
// the hit term matters beyond x = 708 the two-lane e^(−x) leaves its domain: there the per-beam
// form is used instead.

#include <cstddef>
#include <span>

#include "localizer/models/beam_mixture.hpp"

namespace conicloc::localizer {

class BeamLikelihoodSum {
 public:
  /// The mixture of BeamMixture(config, noise, max_range_m).
  BeamLikelihoodSum(const BeamMixtureConfig& config, const RangeNoise& noise, double max_range_m);

  /// Σ_i log p(measured_i | predicted_i), the floor of beam i from its short-reading density
  /// (BeamMixture::short_density: the floor is w_rand/z_max, plus that where z < ẑ); predicted may
  /// be +∞ (no return predicted). `inliers` receives the count of beams within the inlier gate.
  /// Precondition: the three spans have one size.
  double sum(std::span<const double> measured_m, std::span<const double> predicted_m,
             std::span<const double> short_densities, std::size_t& inliers) const;

  /// Σ_i r_i · log max(H e^(−x_i), F_i): each beam's max-mixture term (BeamMixture::
  /// max_log_likelihood, with the short-reading floor where z < ẑ) times its exponent r_i
  /// (`weights`, ObservationModel::weigh_terms). The max form is what makes a per-beam exponent
  /// cheap: r·log max(a, b) = max(r·log a, r·log b), no exp and no log; it is below the
  /// mixture's log-density by at most log 2 per beam, at the crossover only. `log_short_floors`:
  /// log(w_rand/z_max + short density) per beam. Precondition: the spans have one size.
  double weighted_max_sum(std::span<const double> measured_m, std::span<const double> predicted_m,
                          std::span<const double> weights, std::span<const double> log_short_floors,
                          std::size_t& inliers) const;

  /// Σ_i log max(H e^(−x_i), F_i): weighted_max_sum() with every exponent 1.
  double max_sum(std::span<const double> measured_m, std::span<const double> predicted_m,
                 std::span<const double> log_short_floors, std::size_t& inliers) const;

  std::size_t chunk() const { return chunk_; }

 private:
  /// weighted_max_sum(), with every weight 1 where `weights` is empty.
  double max_form(std::span<const double> measured_m, std::span<const double> predicted_m,
                  std::span<const double> weights, std::span<const double> log_short_floors,
                  std::size_t& inliers) const;

  BeamMixture mixture_;          ///< the per-beam form (fallback, and the reference)
  double hit_scale_ = 0.0;       ///< H = w_hit / (√(2π)σ)
  double log_hit_scale_ = 0.0;   ///< log H
  double log_random_density_;    ///< log(w_rand/z_max)
  double inverse_two_variance_;  ///< 1 / 2σ²
  double random_density_;        ///< w_rand / z_max
  double gate_m_;                ///< inlier gate, metres
  double hit_cutoff_;            ///< x beyond which H e^(−x) vanishes against every floor
  std::size_t chunk_ = 1;        ///< beams per product (0: per-beam logs)
};

}  // namespace conicloc::localizer
