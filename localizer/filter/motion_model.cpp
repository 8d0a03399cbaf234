#include "localizer/filter/motion_model.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace conicloc::localizer {

void MotionModel::update_cell(Particle& particle) const {
  const PoseState& s = particle.state;
  // The particle's floor before the move, as the hint for which storey's floor it stands on.
  const double floor_hint_m = s.z - config_.height_above_floor_m;
  const int cell = free_space_.cell_at(s.x, s.y, floor_hint_m, particle.cell);
  particle.cell = cell;
  if (cell >= 0) particle.floor_z = free_space_.floor_z_at(cell, s.x, s.y, floor_hint_m);
}

void MotionModel::follow_floor(Particle& particle) const {
  const double old_floor_z = particle.floor_z;
  update_cell(particle);
  particle.state.z += particle.floor_z - old_floor_z;
}

void MotionModel::place_on_floor(Particle& particle) const {
  update_cell(particle);
  particle.state.z = particle.floor_z + config_.height_above_floor_m;
  particle.state.roll = config_.roll_rad;
  particle.state.pitch = config_.pitch_rad;
}

void MotionModel::level_to(ParticleSet& particles, double roll_rad, double pitch_rad) const {
  for (Particle& particle : particles) {
    particle.state.roll = roll_rad;
    particle.state.pitch = pitch_rad;
  }
}

double MotionModel::xy_sigma(double distance_m, double dt_s) const {
  return config_.xy_sigma_m_per_sqrt_s * std::sqrt(std::max(dt_s, 0.0)) +
         config_.xy_sigma_per_m * distance_m;
}

double MotionModel::velocity_step_xy_sigma(double dt_s) const {
  // The OU velocity is driven by white acceleration of intensity q: its stationary variance is
  // σ_v² = q·T/2, so q = 2σ_v²/T. Over a step dt the white-acceleration model's covariance of
  // (position, velocity) is q·[[dt³/3, dt²/2], [dt²/2, dt]] (Bar-Shalom, Li & Kirubarajan 2001,
  // 6.2.2); given the velocities at both ends, the position keeps its Schur complement
  // q·(dt³/3 − (dt²/2)²/dt) = q·dt³/12: 4 mm per scan at 10 Hz for σ_v = 0.3 m/s, T = 1 s
  // (for dt ≪ T; scans are 0.03–0.25 s apart). predict_velocity() steps by the end velocity
  // (v₁·dt, the Euler step the motion always took) rather than the trapezoid (v₀ + v₁)/2·dt, so
  // the velocity's innovation moves a tracked particle by its whole 1.3 cm per scan, not half.
  // The odometer's noise (xy_sigma: 3 cm per scan at walking speed) was used here before: a
  // second, independent position noise over twice the velocity's own effect, so the scans
  // selected particles by that noise rather than by their velocity, and the cloud learnt no
  // speed. A robot starting from rest without odometry (generated hall, seed 2) was left
  // 14–18 cm behind within 0.4 s while the cloud sat 1 cm wide.
  const double dt = std::max(dt_s, 0.0);
  const double q = 2.0 * config_.velocity_sigma_m_s * config_.velocity_sigma_m_s /
                   std::max(config_.velocity_correlation_s, 1e-6);
  return std::sqrt(q * dt * dt * dt / 12.0);
}

double MotionModel::yaw_sigma(double distance_m, double dyaw_rad, double dt_s) const {
  return config_.yaw_sigma_rad_per_sqrt_s * std::sqrt(std::max(dt_s, 0.0)) +
         config_.yaw_sigma_per_rad * std::abs(dyaw_rad) + config_.yaw_sigma_rad_per_m * distance_m;
}

void MotionModel::move(Particle& particle, const Eigen::Vector2d& step, double dyaw,
                       double xy_sigma, double yaw_sigma, std::mt19937_64& rng,
                       std::normal_distribution<double>& normal) const {
  const double ndx = step.x() + xy_sigma * normal(rng);
  const double ndy = step.y() + xy_sigma * normal(rng);
  const double ndyaw = dyaw + yaw_sigma * normal(rng);
  PoseState& s = particle.state;
  // z is carried as the height above the floor under the particle, so it follows the floor
  // without lag where that floor rises with x, y (a stair) and jumps with the storey.
  const double height_m = s.z - particle.floor_z;
  const double floor_before_m = particle.floor_z;
  const double c = std::cos(s.yaw);
  const double sn = std::sin(s.yaw);
  s.x += c * ndx - sn * ndy;
  s.y += sn * ndx + c * ndy;
  s.yaw = angle_difference(s.yaw + ndyaw, 0.0);
  update_cell(particle);
  particle.floor_rise_m = particle.floor_z - floor_before_m;
  // Ornstein-Uhlenbeck step of the height toward the mounting: bounded spread.
  const double keep = 1.0 - config_.mounting_pull;
  const double h_mount = config_.height_above_floor_m;
  s.z = particle.floor_z + h_mount + keep * (height_m - h_mount) + config_.z_sigma_m * normal(rng);
  s.roll =
      config_.roll_rad + keep * (s.roll - config_.roll_rad) + config_.roll_sigma_rad * normal(rng);
  s.pitch = config_.pitch_rad + keep * (s.pitch - config_.pitch_rad) +
            config_.pitch_sigma_rad * normal(rng);
}

void MotionModel::predict(ParticleSet& particles, const Pose3& T_prev_curr, double dt_s,
                          std::mt19937_64& rng) const {
  // The planar part of the motion in the previous sensor frame; the sensor is near level, so
  // roll and pitch of the increment are left to the mounting model.
  const double dx = T_prev_curr.translation().x();
  const double dy = T_prev_curr.translation().y();
  const double dyaw = yaw_of(T_prev_curr);
  const double distance = std::hypot(dx, dy);
  const double sigma_xy = xy_sigma(distance, dt_s);
  const double sigma_yaw = yaw_sigma(distance, dyaw, dt_s);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (Particle& particle : particles)
    move(particle, Eigen::Vector2d(dx, dy), dyaw, sigma_xy, sigma_yaw, rng, normal);
}

namespace {
/// `v` shortened to `limit` where it is longer.
Eigen::Vector2d at_most(const Eigen::Vector2d& v, double limit) {
  const double length = std::hypot(v.x(), v.y());
  return length > limit ? Eigen::Vector2d(v * (limit / length)) : v;
}
}  // namespace

void MotionModel::predict_velocity(ParticleSet& particles, const Eigen::Vector3d& mean, double dt_s,
                                   std::mt19937_64& rng,
                                   const std::optional<MeasuredTurn>& turn) const {
  predict_velocity_about(
      particles, [&](std::size_t) -> const Eigen::Vector3d& { return mean; }, dt_s, rng, turn);
}

void MotionModel::predict_velocity(ParticleSet& particles, std::span<const Eigen::Vector3d> means,
                                   double dt_s, std::mt19937_64& rng,
                                   const std::optional<MeasuredTurn>& turn) const {
  assert(means.size() == particles.size());
  predict_velocity_about(
      particles, [&](std::size_t i) -> const Eigen::Vector3d& { return means[i]; }, dt_s, rng,
      turn);
}

template <typename MeanOf>
void MotionModel::predict_velocity_about(ParticleSet& particles, MeanOf mean_of, double dt_s,
                                         std::mt19937_64& rng,
                                         const std::optional<MeasuredTurn>& turn) const {
  const double dt = std::max(dt_s, 0.0);
  const double keep = std::exp(-dt / std::max(config_.velocity_correlation_s, 1e-6));
  const double innovation = std::sqrt(std::max(1.0 - keep * keep, 0.0));
  const double speed_step = config_.velocity_sigma_m_s * innovation;
  const double yaw_rate_step = config_.yaw_rate_sigma_rad_s * innovation;
  // r: the position's variance once the velocity at the step's end is known.
  const double within_step = velocity_step_xy_sigma(dt);
  const double r = within_step * within_step;
  std::normal_distribution<double> normal(0.0, 1.0);
  for (std::size_t i = 0; i < particles.size(); ++i) {
    Particle& particle = particles[i];
    const Eigen::Vector3d& mean = mean_of(i);
    // The OU step of the velocity's mean and variance, v ~ N(v̂, P) per axis.
    double vx = mean.x() + keep * (particle.velocity_x - mean.x());
    double vy = mean.y() + keep * (particle.velocity_y - mean.y());
    const double p = keep * keep * particle.velocity_variance + speed_step * speed_step;
    // The displacement d = v·dt + e, e ~ N(0, r): d ~ N(v̂·dt, P·dt² + r), drawn; given it, the
    // velocity is v̂ + K·(d − v̂·dt), K = P·dt / (P·dt² + r), with variance P·r / (P·dt² + r).
    const double s = p * dt * dt + r;
    const double dx = vx * dt + std::sqrt(s) * normal(rng);
    const double dy = vy * dt + std::sqrt(s) * normal(rng);
    if (s > 0.0) {
      const double gain = p * dt / s;
      vx += gain * (dx - vx * dt);
      vy += gain * (dy - vy * dt);
      particle.velocity_variance = p * r / s;
    } else {
      particle.velocity_variance = p;
    }
    // The speed bound holds for the velocity carried on as for the step drawn.
    const Eigen::Vector2d velocity = at_most(Eigen::Vector2d(vx, vy), config_.max_speed_m_s);
    const Eigen::Vector2d step = at_most(Eigen::Vector2d(dx, dy), config_.max_speed_m_s * dt);
    particle.yaw_rate =
        std::clamp(mean.z() + keep * (particle.yaw_rate - mean.z()) + yaw_rate_step * normal(rng),
                   -config_.max_yaw_rate_rad_s, config_.max_yaw_rate_rad_s);
    particle.velocity_x = velocity.x();
    particle.velocity_y = velocity.y();
    double dyaw = particle.yaw_rate * dt;
    const double distance = step.norm();
    double sigma_yaw = yaw_sigma(distance, dyaw, dt);
    if (turn && dt > 0.0) {
      dyaw = turn->yaw_rad;
      particle.yaw_rate = dyaw / dt;
      sigma_yaw = turn->sigma_rad;
    }
    move(particle, step, dyaw, 0.0, sigma_yaw, rng, normal);  // the step's noise is drawn
  }
}

void MotionModel::draw_initial_velocity(Particle& particle, std::mt19937_64& rng) const {
  std::normal_distribution<double> normal(0.0, 1.0);
  particle.velocity_x = 0.0;
  particle.velocity_y = 0.0;
  particle.velocity_variance = config_.initial_speed_sigma_m_s * config_.initial_speed_sigma_m_s;
  particle.yaw_rate = config_.yaw_rate_sigma_rad_s * normal(rng);
}

}  // namespace conicloc::localizer
