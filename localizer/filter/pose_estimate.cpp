#include "localizer/filter/pose_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace conicloc::localizer {

namespace {

Vector6 difference(const PoseState& a, const PoseState& b) {
  Vector6 d;
  d << a.x - b.x, a.y - b.y, a.z - b.z, angle_difference(a.roll, b.roll),
      angle_difference(a.pitch, b.pitch), angle_difference(a.yaw, b.yaw);
  return d;
}

/// ModeAnchor::MostWeight: of the heaviest particles of the cells (mode_radius_m squares in x, y;
/// mode_z_m in z, mode_yaw_rad in yaw) holding the most weight, the one whose mode holds the most.
/// Cells only shortlist: a mode may straddle two.
const Particle& most_weight_anchor(const ParticleSet& particles, const PoseEstimateConfig& config) {
  constexpr std::size_t kShortlist = 8;
  struct Cell {
    double mass = 0.0;
    const Particle* heaviest = nullptr;
  };
  std::unordered_map<std::uint64_t, Cell> cells;
  const auto index = [](double value, double size, int bits) {
    return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(value / size)) &
                                      ((std::int64_t{1} << bits) - 1));
  };
  for (const Particle& p : particles) {
    // 20 bits each of x and y, 8 of z, 16 of yaw: distinct cells over ±500 km in x, y and
    // ±128 m in z at the default sizes.
    const std::uint64_t key = index(p.state.x, config.mode_radius_m, 20) << 44 |
                              index(p.state.y, config.mode_radius_m, 20) << 24 |
                              index(p.state.z, config.mode_z_m, 8) << 16 |
                              index(p.state.yaw, config.mode_yaw_rad, 16);
    Cell& cell = cells[key];
    cell.mass += std::exp(p.log_weight);
    if (!cell.heaviest || p.log_weight > cell.heaviest->log_weight) cell.heaviest = &p;
  }
  std::vector<const Cell*> shortlist;
  for (const auto& entry : cells) shortlist.push_back(&entry.second);
  // Ordered by mass, then by the earlier particle: nothing depends on the hash map's order.
  const auto heavier = [](const Cell* a, const Cell* b) {
    return a->mass != b->mass ? a->mass > b->mass : a->heaviest < b->heaviest;
  };
  const std::size_t keep = std::min(kShortlist, shortlist.size());
  std::partial_sort(shortlist.begin(), shortlist.begin() + static_cast<std::ptrdiff_t>(keep),
                    shortlist.end(), heavier);
  const Particle* best = nullptr;
  double best_mass = -1.0;
  for (std::size_t c = 0; c < keep; ++c) {
    const Particle& candidate = *shortlist[c]->heaviest;
    double mass = 0.0;
    for (const Particle& p : particles)
      if (in_mode(p.state, candidate.state, config)) mass += std::exp(p.log_weight);
    if (mass > best_mass) best = &candidate, best_mass = mass;
  }
  return *best;
}

}  // namespace

bool in_mode(const PoseState& state, const PoseState& anchor, const PoseEstimateConfig& config) {
  return std::hypot(state.x - anchor.x, state.y - anchor.y) <= config.mode_radius_m &&
         std::abs(state.z - anchor.z) <= config.mode_z_m &&
         std::abs(angle_difference(state.yaw, anchor.yaw)) <= config.mode_yaw_rad;
}

PoseEstimate estimate_pose(const ParticleSet& particles, const PoseEstimateConfig& config,
                           ModeAnchor anchor_choice) {
  PoseEstimate estimate;
  if (particles.empty()) return estimate;
  const PoseState& anchor = anchor_choice == ModeAnchor::MostWeight
                                ? most_weight_anchor(particles, config).state
                                : std::max_element(particles.begin(), particles.end(),
                                                   [](const Particle& a, const Particle& b) {
                                                     return a.log_weight < b.log_weight;
                                                   })
                                      ->state;
  // Weighted mean of the mode: linear for x, y, z; about the anchor for the angles, which
  // is the circular mean for the small spreads inside a mode.
  Vector6 sum = Vector6::Zero();
  double mass = 0.0;
  for (const Particle& p : particles) {
    if (!in_mode(p.state, anchor, config)) continue;
    const Vector6 d = difference(p.state, anchor);
    const double w = std::exp(p.log_weight);
    sum += w * d;
    mass += w;
  }
  PoseState mean = anchor;
  if (mass > 0.0) {
    const Vector6 offset = sum / mass;
    mean.x += offset(0);
    mean.y += offset(1);
    mean.z += offset(2);
    mean.roll = angle_difference(mean.roll + offset(3), 0.0);
    mean.pitch = angle_difference(mean.pitch + offset(4), 0.0);
    mean.yaw = angle_difference(mean.yaw + offset(5), 0.0);
  }
  Matrix6 covariance = Matrix6::Zero();
  double total = 0.0;
  for (const Particle& p : particles) {
    const double w = std::exp(p.log_weight);
    const Vector6 d = difference(p.state, mean);
    covariance.noalias() += w * d * d.transpose();
    total += w;
  }
  estimate.state = mean;
  estimate.covariance = total > 0.0 ? Matrix6(covariance / total) : covariance;
  estimate.mode_weight = total > 0.0 ? mass / total : 0.0;
  return estimate;
}

}  // namespace conicloc::localizer
