#pragma once
// The sensor's tilt measured from the scan: roll and pitch at the likelihood's peak.
//
// Why: the mounting model keeps every particle's roll and pitch within ~0.1° of the nominal
// mounting, but a hand-held sensor sways by 2–3° at the walking rhythm, and a robot tilts when it
// brakes or crosses a threshold. No particle then stands at the sensor's tilt, and the true x, y,
// yaw explain the scan poorly: a return at range r misses its surface by about r·Δθ (30 m × 2° ≈
// 1 m), so the far walls and the floor rings count as outliers. Measured on a hand-held run
// without odometry in a building of long corridors (PNU, conic-beam, `--init` at the truth): with
// x, y within 5 cm of the truth, the best particle explained 17–35 % of the beams (70 % while the
// sensor was level), the lost test fired three times, and conic-segment lost the sensor.
//
// The tilt is the direction of gravity in the sensor frame. It is the same for every hypothesis
// (yaw does not enter it: R = Rz(yaw)·Ry(pitch)·Rx(roll)) and the scan measures it sharply (the
// floor and ceiling rings, the verticals of the walls). So it is a nuisance parameter, profiled
// out once per scan for the whole cloud: at one pose that explains the scan (the previous scan's
// best particle, carried by the cloud's motion) a compass search over (roll, pitch) climbs the
// likelihood, and the particles take the tilt it reached (MotionModel::level_to).

#include <functional>
#include <optional>

#include "localizer/filter/particle.hpp"
#include "localizer/models/observation_model.hpp"

namespace conicloc::localizer {

struct ScanTiltConfig {
  bool enabled = true;
  double first_step_rad = 0.00873;  ///< 0.5°: a hand-held sensor's tilt changes ~1° per scan
  double min_step_rad = 0.00035;    ///< 0.02°: 1 cm at 30 m
  int max_evaluations = 40;         ///< likelihood evaluations of the search, per scan
  double max_tilt_rad = 0.35;       ///< 20°: roll and pitch about the mounting stay within
  /// The pose searched from must explain at least this share of the scan's terms, or the tilt it
  /// reaches says nothing (a lost cloud's best particle).
  double min_inlier_fraction = 0.2;
  /// The measured tilt replaces the one the cloud held only where it explains the scan better by
  /// at least this many nats of the tempered log-likelihood (what the scan is worth as independent
  /// terms): Akaike's criterion for two more parameters, ΔlnL > 2. A level robot's scans, fitted
  /// for a tilt, gain a fraction of a nat from fitting noise — roll about a corridor's axis is
  /// seen weakly, and the fit wanders by 0.1–0.2° — and keep their tilt; a swaying sensor's gain
  /// tens to hundreds.
  double min_gain_nats = 2.0;
};

struct MeasuredTilt {
  double roll_rad = 0.0;
  double pitch_rad = 0.0;
  ObservationScore score;             ///< at the tilt reached
  double start_log_likelihood = 0.0;  ///< at the anchor's own tilt
  /// −∂²ln p/∂roll², −∂²ln p/∂pitch² at the tilt reached (un-tempered; central differences over
  /// ±2·min_step_rad; 0 where the likelihood is not concave there): τ·curvature is the inverse
  /// variance of the tilt the scan shows.
  double roll_curvature = 0.0;
  double pitch_curvature = 0.0;
  int evaluations = 0;  ///< of the likelihood, the 4 for the curvatures included
};

/// Compass search over the roll and pitch of `anchor` (x, y, z, yaw held) for the highest
/// `log_likelihood`, within max_tilt_rad of (`mounting_roll_rad`, `mounting_pitch_rad`).
/// Nothing when disabled, or when the pose it reached explains less than min_inlier_fraction.
std::optional<MeasuredTilt> measure_tilt(
    const PoseState& anchor, double mounting_roll_rad, double mounting_pitch_rad,
    const ScanTiltConfig& config,
    const std::function<ObservationScore(const PoseState&)>& log_likelihood);

}  // namespace conicloc::localizer
