#include "localizer/filter/scan_tilt.hpp"

#include <cmath>

#include "localizer/filter/compass_search.hpp"

namespace conicloc::localizer {

std::optional<MeasuredTilt> measure_tilt(
    const PoseState& anchor, double mounting_roll_rad, double mounting_pitch_rad,
    const ScanTiltConfig& config,
    const std::function<ObservationScore(const PoseState&)>& log_likelihood) {
  if (!config.enabled || config.max_evaluations < 1) return std::nullopt;
  PoseState peak = anchor;
  MeasuredTilt tilt;
  tilt.score = log_likelihood(peak);
  tilt.start_log_likelihood = tilt.score.log_likelihood;
  tilt.evaluations = 1;
  // Axis 0 is roll, axis 1 pitch.
  tilt.evaluations +=
      compass_search(2, config.first_step_rad, config.min_step_rad, config.max_evaluations - 1,
                     [&](std::size_t axis, double step) {
                       PoseState candidate = peak;
                       double& angle = axis == 0 ? candidate.roll : candidate.pitch;
                       const double mounting = axis == 0 ? mounting_roll_rad : mounting_pitch_rad;
                       angle += step;
                       if (std::abs(angle - mounting) > config.max_tilt_rad) return Probe::Skipped;
                       const ObservationScore score = log_likelihood(candidate);
                       // `>` is false for NaN: a pose the model cannot score is never taken.
                       if (!(score.log_likelihood > tilt.score.log_likelihood)) return Probe::Worse;
                       peak = candidate;
                       tilt.score = score;
                       return Probe::Improved;
                     });
  if (!(tilt.score.inlier_fraction >= config.min_inlier_fraction)) return std::nullopt;
  tilt.roll_rad = peak.roll;
  tilt.pitch_rad = peak.pitch;
  // Curvature c = −(ℓ(θ + h) + ℓ(θ − h) − 2ℓ(θ)) / h² along each axis.
  const double h = 2.0 * config.min_step_rad;
  const auto curvature = [&](double PoseState::*angle) {
    PoseState plus = peak, minus = peak;
    plus.*angle += h;
    minus.*angle -= h;
    tilt.evaluations += 2;
    const double c = -(log_likelihood(plus).log_likelihood + log_likelihood(minus).log_likelihood -
                       2.0 * tilt.score.log_likelihood) /
                     (h * h);
    return std::isfinite(c) && c > 0.0 ? c : 0.0;
  };
  tilt.roll_curvature = curvature(&PoseState::roll);
  tilt.pitch_curvature = curvature(&PoseState::pitch);
  return tilt;
}

}  // namespace conicloc::localizer
