#pragma once
// Motion model of the filter: moves every particle by the relative motion since the last scan
// (from odometry, or without it by the particle's own velocity) with noise on x, y and yaw, and
// keeps z, roll
// and pitch near the sensor's mounting, z riding on the floor under the particle (the floor
// height at its x, y in its cell: flat on a storey, rising along a stair).

#include <cstddef>
#include <optional>
#include <random>
#include <span>

#include "localizer/filter/free_space.hpp"
#include "localizer/filter/particle.hpp"

namespace conicloc::localizer {

struct MotionModelConfig {
  // Planar noise: σ = base·sqrt(dt) + proportional·|motion| (odometry-style, Thrun et al. 5.4).
  // Without odometry the translation's noise is the velocity's own (velocity_step_xy_sigma);
  // the heading's stays this one where no turn is measured from the scans.
  double xy_sigma_m_per_sqrt_s = 0.08;    ///< translation random walk, per axis
  double xy_sigma_per_m = 0.05;           ///< per metre travelled, per axis
  double yaw_sigma_rad_per_sqrt_s = 0.1;  ///< heading random walk (turns start abruptly)
  double yaw_sigma_per_rad = 0.05;        ///< per radian turned
  double yaw_sigma_rad_per_m = 0.01;      ///< per metre travelled
  // The mounting: the sensor is carried at a fixed height above the floor, nearly level.
  double height_above_floor_m = 1.0;  ///< sensor apex height over the floor of its cell
  double roll_rad = 0.0;
  double pitch_rad = 0.0;
  double z_sigma_m = 0.01;         ///< noise of the height above the floor, per scan
  double roll_sigma_rad = 0.002;   ///< per scan
  double pitch_sigma_rad = 0.002;  ///< per scan
  double mounting_pull = 0.5;      ///< fraction of the offset from the mounting removed per scan
  // Without odometry each particle carries its own planar velocity: an Ornstein-Uhlenbeck process
  // about the cloud's mean velocity (the integrated OU / Singer model, Bar-Shalom, Li &
  // Kirubarajan 2001, 6.2.3), v ← v̄ + e^(−dt/T)(v − v̄) + σ_v·√(1 − e^(−2dt/T))·w. The cloud
  // thus keeps a bounded spread of velocities around its estimate, and the scans choose among
  // them: a particle moving at the wrong speed drifts off what the scans show and loses weight,
  // so the mean follows the sensor's real motion instead of a guess from past estimates.
  double velocity_sigma_m_s = 0.3;      ///< stationary spread about the mean, forward and left
  double yaw_rate_sigma_rad_s = 0.3;    ///< stationary spread of the yaw rate
  double velocity_correlation_s = 1.0;  ///< T: how long a velocity deviation persists
  /// Velocity spread of new particles (a start or a recovery): the sensor may already be moving
  /// at walking speed in any direction.
  double initial_speed_sigma_m_s = 1.0;
  /// While a global start's or a recovery's cloud searches, each of at most this many of its modes
  /// reverts to its own mean velocity instead of the cloud's (hypothesis_velocities.hpp).
  std::size_t velocity_hypotheses = 64;
  double max_speed_m_s = 3.0;  ///< velocities are clamped to these
  double max_yaw_rate_rad_s = 3.0;
};

/// A turn measured from the scans themselves (ScanTurn).
struct MeasuredTurn {
  double yaw_rad = 0.0;
  double sigma_rad = 0.0;
};

class MotionModel {
 public:
  MotionModel(const MotionModelConfig& config, const FreeSpace& free_space)
      : config_(config), free_space_(free_space) {}

  /// Moves each particle by T_prev_curr (sensor frame at the previous scan → current scan) with
  /// noise, over `dt_s` seconds. Draws all noise serially from `rng` (repeatable).
  void predict(ParticleSet& particles, const Pose3& T_prev_curr, double dt_s,
               std::mt19937_64& rng) const;

  /// Without odometry: steps each particle's velocity (OU about `mean`: forward, left in m/s, yaw
  /// rate in rad/s, the cloud's weighted mean) and moves the particle over `dt_s` by a
  /// displacement drawn from what its velocity and that velocity's variance allow, plus the
  /// acceleration within the step (velocity_step_xy_sigma); the velocity is then updated with the
  /// displacement drawn (a Kalman step per particle: the velocity is linear-Gaussian given the
  /// positions, Rao-Blackwellised as in Schön, Gustafsson & Nordlund 2005), so the scan that
  /// selects a displacement selects its velocity. The heading's noise is predict()'s. A turn
  /// measured from the scans (`turn`, see ScanTurn) replaces the particles' yaw rates, with the
  /// measurement's noise.
  /// Draws all noise serially from `rng` (repeatable).
  void predict_velocity(ParticleSet& particles, const Eigen::Vector3d& mean, double dt_s,
                        std::mt19937_64& rng,
                        const std::optional<MeasuredTurn>& turn = std::nullopt) const;
  /// The same with a mean per particle (`means[i]` for particles[i]): the velocity of the
  /// hypothesis the particle stands for (hypothesis_velocities.hpp). Precondition:
  /// means.size() == particles.size().
  void predict_velocity(ParticleSet& particles, std::span<const Eigen::Vector3d> means, double dt_s,
                        std::mt19937_64& rng,
                        const std::optional<MeasuredTurn>& turn = std::nullopt) const;

  /// A new particle's velocity: not yet seen, zero with variance initial_speed_sigma_m_s² forward
  /// and left; a yaw rate drawn from its stationary spread.
  void draw_initial_velocity(Particle& particle, std::mt19937_64& rng) const;

  /// Gives every particle the tilt measured from the scan (scan_tilt.hpp), without noise: the
  /// tilt is profiled out for the whole cloud, not sampled. Noise on it would make the scan select
  /// particles by their tilt — 0.1° moves a return at 30 m by 5 cm — and that selection, blind to
  /// the velocities the particles carry, lets the cloud's speed drift where nothing else is seen
  /// (measured along a corridor, hand-held without odometry: the effective sample size halved and
  /// the estimate fell 1–2 m behind in two of four seeds).
  void level_to(ParticleSet& particles, double roll_rad, double pitch_rad) const;

  /// Sets z, roll and pitch of a particle from its cell and the mounting (no noise) and updates
  /// its cell; used by initialisation.
  void place_on_floor(Particle& particle) const;

  /// Updates particle.cell and particle.floor_z (the floor height under its x, y — it varies
  /// along a stair) without moving z; keeps the old floor outside every cell.
  void update_cell(Particle& particle) const;

  /// update_cell(), and z moves with the floor: the height above the floor is kept (after an xy
  /// jump such as roughening, a particle on a stair stays at the mounting height over the flight).
  void follow_floor(Particle& particle) const;

  const MotionModelConfig& config() const { return config_; }

  /// The mounting height above the floor, e.g. learnt from an initial pose.
  void set_height_above_floor(double height_m) { config_.height_above_floor_m = height_m; }

 private:
  /// predict_velocity() about `mean_of(i)` for particles[i] (both overloads, without copying a
  /// cloud-wide mean per particle on every tracked scan).
  template <typename MeanOf>
  void predict_velocity_about(ParticleSet& particles, MeanOf mean_of, double dt_s,
                              std::mt19937_64& rng, const std::optional<MeasuredTurn>& turn) const;
  /// Moves a particle by the planar motion (step, dyaw) in its own frame with noise of these
  /// std. devs., then z, roll and pitch by the mounting model (shared by both predictions).
  void move(Particle& particle, const Eigen::Vector2d& step, double dyaw, double xy_sigma,
            double yaw_sigma, std::mt19937_64& rng, std::normal_distribution<double>& normal) const;
  /// The planar noise of a motion: σ = base·√dt + proportional·|motion| (Thrun et al. 5.4).
  double xy_sigma(double distance_m, double dt_s) const;
  /// The position noise of a step by a particle's own velocity, per axis: what the acceleration
  /// within the step adds once the velocity at its end is known, σ² = q·dt³/12 with the OU's
  /// acceleration intensity q = 2σ_v²/T (see the .cpp for why it is not the odometer's).
  double velocity_step_xy_sigma(double dt_s) const;
  double yaw_sigma(double distance_m, double dyaw_rad, double dt_s) const;

  MotionModelConfig config_;
  const FreeSpace& free_space_;
};

}  // namespace conicloc::localizer
