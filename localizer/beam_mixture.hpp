#pragma once
// The robust per-beam range likelihood (Thrun, Burgard & Fox, Probabilistic Robotics, 6.3):
//   p(z | ẑ) = w_hit·N(z; ẑ, σ) + w_short·λe^(−λz)·[z < ẑ] + w_rand / z_max,
// a hit near the predicted range ẑ, a short reading from clutter the map lacks (people,
// furniture), and a uniform floor. Max-range readings carry no return and are not scored.
// Everything but the hit term depends on the measurement alone, so it is precomputed per beam.

#include <cmath>

namespace conicloc::localizer {

struct BeamMixtureConfig {
  double sigma_hit_m = 0.05;  ///< range noise plus map error
  double hit_weight = 0.7;
  double short_weight = 0.15;
  double short_rate_per_m = 0.2;  ///< λ of the exponential short-reading density
  double random_weight = 0.15;
  double max_range_m = 100.0;  ///< support of the uniform part
  double inlier_sigmas = 3.0;  ///< |z − ẑ| below this many σ counts as explained
};

/// The measurement-only parts of one beam's mixture, in the log domain.
struct BeamFloor {
  double with_short = 0.0;     ///< log(w_short·λe^(−λz) + w_rand/z_max): used when z < ẑ
  double without_short = 0.0;  ///< log(w_rand/z_max): z ≥ ẑ, or no surface predicted
};

class BeamMixture {
 public:
  explicit BeamMixture(const BeamMixtureConfig& config)
      : config_(config),
        log_hit_scale_(std::log(config.hit_weight / (std::sqrt(2.0 * M_PI) * config.sigma_hit_m))),
        inverse_two_variance_(0.5 / (config.sigma_hit_m * config.sigma_hit_m)),
        random_density_(config.random_weight / config.max_range_m) {}

  BeamFloor floor(double measured_m) const {
    const double short_density = config_.short_weight * config_.short_rate_per_m *
                                 std::exp(-config_.short_rate_per_m * measured_m);
    return {std::log(short_density + random_density_), std::log(random_density_)};
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
    const double log_hit = log_hit_scale_ - residual * residual * inverse_two_variance_;
    inlier = std::abs(residual) <= config_.inlier_sigmas * config_.sigma_hit_m;
    // log(e^a + e^b) = max + log1p(e^(min − max)); beyond ~37 nats the smaller term is below
    // double resolution, so the exp/log1p pair is skipped (most beams of a wrong pose).
    const double hi = std::max(log_hit, log_floor);
    const double gap = std::min(log_hit, log_floor) - hi;
    return gap < -37.0 ? hi : hi + std::log1p(std::exp(gap));
  }

  const BeamMixtureConfig& config() const { return config_; }

 private:
  BeamMixtureConfig config_;
  double log_hit_scale_;
  double inverse_two_variance_;
  double random_density_;
};

}  // namespace conicloc::localizer
