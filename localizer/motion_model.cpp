#include "localizer/motion_model.hpp"

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

void MotionModel::predict(ParticleSet& particles, const Pose3& T_prev_curr, double dt_s,
                          std::mt19937_64& rng) const {
  // The planar part of the motion in the previous sensor frame; the sensor is near level, so
  // roll and pitch of the increment are left to the mounting model below.
  const double dx = T_prev_curr.translation().x();
  const double dy = T_prev_curr.translation().y();
  const double dyaw = yaw_of(T_prev_curr);
  const double distance = std::hypot(dx, dy);
  const double root_dt = std::sqrt(std::max(dt_s, 0.0));
  const double xy_sigma =
      config_.xy_sigma_m_per_sqrt_s * root_dt + config_.xy_sigma_per_m * distance;
  const double yaw_sigma = config_.yaw_sigma_rad_per_sqrt_s * root_dt +
                           config_.yaw_sigma_per_rad * std::abs(dyaw) +
                           config_.yaw_sigma_rad_per_m * distance;
  std::normal_distribution<double> normal(0.0, 1.0);
  const double keep = 1.0 - config_.mounting_pull;
  for (Particle& particle : particles) {
    PoseState& s = particle.state;
    // z is carried as the height above the floor under the particle, so it follows the floor
    // without lag where that floor rises with x, y (a stair) and jumps with the storey.
    const double height_m = s.z - particle.floor_z;
    const double floor_before_m = particle.floor_z;
    const double ndx = dx + xy_sigma * normal(rng);
    const double ndy = dy + xy_sigma * normal(rng);
    const double c = std::cos(s.yaw);
    const double sn = std::sin(s.yaw);
    s.x += c * ndx - sn * ndy;
    s.y += sn * ndx + c * ndy;
    s.yaw = angle_difference(s.yaw + dyaw + yaw_sigma * normal(rng), 0.0);
    update_cell(particle);
    particle.floor_rise_m = particle.floor_z - floor_before_m;
    // Ornstein-Uhlenbeck step of the height toward the mounting: bounded spread.
    const double h_mount = config_.height_above_floor_m;
    s.z =
        particle.floor_z + h_mount + keep * (height_m - h_mount) + config_.z_sigma_m * normal(rng);
    s.roll = config_.roll_rad + keep * (s.roll - config_.roll_rad) +
             config_.roll_sigma_rad * normal(rng);
    s.pitch = config_.pitch_rad + keep * (s.pitch - config_.pitch_rad) +
              config_.pitch_sigma_rad * normal(rng);
  }
}

}  // namespace conicloc::localizer
