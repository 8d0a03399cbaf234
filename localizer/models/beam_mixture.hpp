#pragma once
// The robust per-beam range likelihood (Thrun, Burgard & Fox, Probabilistic Robotics, 6.3):
//   p(z | ẑ) = w_hit·N(z; ẑ, σ) + w_short·λe^(−λz)·[z < ẑ] + w_rand / z_max,
// a hit near the predicted range ẑ, a short reading from clutter the map lacks (people,
// furniture), and a uniform floor. Max-range readings carry no return and are not scored.
// Everything but the hit term depends on the measurement alone, so it is precomputed per beam.
// σ and the inlier gate are the sensor's range noise (RangeNoise), z_max its maximum range.

#include <cmath>
#include <limits>

#include "localizer/models/range_sensor.hpp"

namespace conicloc::localizer {

/// The mixture's weights: what share of the readings is a hit, a short reading or random.
struct BeamMixtureConfig {
  double hit_weight = 0.7;
  double short_weight = 0.15;
  double short_rate_per_m = 0.2;  ///< λ of the exponential short-reading density
  double random_weight = 0.15;    ///< spread uniformly over [0, z_max]
};

/// The measurement-only parts of one beam's mixture, in the log domain.
struct BeamFloor {
  double with_short = 0.0;     ///< log(w_short·λe^(−λz) + w_rand/z_max): used when z < ẑ
  double without_short = 0.0;  ///< log(w_rand/z_max): z ≥ ẑ, or no surface predicted
  double with_short_density = 0.0;  ///< the same two, linear
  double without_short_density = 0.0;
};

class BeamMixture {
 public:
  /// σ_hit and the inlier gate from `noise`; z_max = `max_range_m`.
  BeamMixture(const BeamMixtureConfig& config, const RangeNoise& noise, double max_range_m)
      : config_(config),
        noise_(noise),
        log_hit_scale_(std::log(config.hit_weight / (std::sqrt(2.0 * M_PI) * noise.sigma_m))),
        inverse_two_variance_(0.5 / (noise.sigma_m * noise.sigma_m)),
        random_density_(config.random_weight / max_range_m),
        hit_scale_(std::exp(log_hit_scale_)),
        // Beyond this x = (z − ẑ)²/2σ² the hit density is below 2⁻⁶⁰ of the smallest floor: the
        // sum rounds to the floor.
        hit_cutoff_(random_density_ > 0.0 ? log_hit_scale_ - std::log(random_density_) + 42.0
                                          : std::numeric_limits<double>::infinity()) {}

  BeamFloor floor(double measured_m) const { return floor_from_short(short_density(measured_m)); }
  /// w_short·λe^(−λz): the short-reading density of a reading z (without the uniform floor).
  double short_density(double measured_m) const {
    return config_.short_weight * config_.short_rate_per_m *
           std::exp(-config_.short_rate_per_m * measured_m);
  }
  /// The floor of a beam whose short-reading density is `short_density`.
  BeamFloor floor_from_short(double short_density) const {
    return {std::log(short_density + random_density_), std::log(random_density_),
            short_density + random_density_, random_density_};
  }

  /// The floor of a term that has no short readings (both cases use log(w_rand/z_max)).
  BeamFloor floor_without_short() const {
    const double log_random = std::log(random_density_);
    return {log_random, log_random, random_density_, random_density_};
  }

  /// log p(z | ẑ); ẑ = +∞ (no surface predicted) leaves only the floor. `inlier` is set when the
  /// residual is within the inlier gate.
  double log_likelihood(double measured_m, double predicted_m, const BeamFloor& floor,
                        bool& inlier) const {
    const double residual = measured_m - predicted_m;  // −∞ when nothing is predicted
    if (std::isnan(residual)) {
      inlier = false;
      return floor.without_short;
    }
    const double log_floor = residual < 0.0 ? floor.with_short : floor.without_short;
    const double x = residual * residual * inverse_two_variance_;
    inlier = std::abs(residual) <= noise_.inlier_gate_m();
    // Far from the prediction (most beams of a wrong pose) only the floor is left.
    if (x > hit_cutoff_) return log_floor;
    // log(H e^(−x) + F): the floor density F ≥ w_rand/z_max > 0 bounds the sum away from 0, so the
    // linear form is as exact as log-sum-exp and needs one exp and one log (log1p is ~3× a log).
    const double floor_density =
        residual < 0.0 ? floor.with_short_density : floor.without_short_density;
    if (floor_density > 0.0) return std::log(hit_scale_ * std::exp(-x) + floor_density);
    // No floor (w_rand = 0): log-sum-exp, log(e^a + e^b) = max + log1p(e^(min − max)).
    const double log_hit = log_hit_scale_ - x;
    const double hi = std::max(log_hit, log_floor);
    const double gap = std::min(log_hit, log_floor) - hi;
    return gap < -37.0 ? hi : hi + std::log1p(std::exp(gap));
  }

  /// The max-mixture form (Olson & Agarwal, "Inference on networks of mixtures for robust robot
  /// mapping", 2012) without short readings: log max(hit density, w_rand/z_max). Below log p(z | ẑ)
  /// by at most log 2, equal to it within F/hit (< 10⁻³ for inliers at the defaults) away from the
  /// crossover; no exp or log, for terms that are evaluated millions of times per scan
  /// (conic-segment).
  double max_log_likelihood(double residual_m, const BeamFloor& floor, bool& inlier) const {
    return max_log_likelihood_squared(residual_m * residual_m, floor, inlier);
  }
  /// The same from the squared residual (m²).
  double max_log_likelihood_squared(double squared_residual_m2, const BeamFloor& floor,
                                    bool& inlier) const {
    const double gate = noise_.inlier_gate_m();
    inlier = squared_residual_m2 <= gate * gate;
    const double log_hit = log_hit_scale_ - squared_residual_m2 * inverse_two_variance_;
    return std::isnan(log_hit) ? floor.without_short : std::max(log_hit, floor.without_short);
  }

 private:
  BeamMixtureConfig config_;
  RangeNoise noise_;
  double log_hit_scale_;
  double inverse_two_variance_;
  double random_density_;
  double hit_scale_;   ///< w_hit / (√(2π)σ)
  double hit_cutoff_;  ///< x beyond which the hit term vanishes against any floor
};

}  // namespace conicloc::localizer
