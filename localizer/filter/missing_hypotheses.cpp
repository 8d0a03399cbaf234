#include "localizer/filter/missing_hypotheses.hpp"

#include <cmath>

namespace conicloc::localizer {

std::vector<PlanCandidate> missing_hypotheses(const ParticleSet& particles,
                                              const std::vector<PlanCandidate>& candidates,
                                              const PoseEstimateConfig& mode,
                                              double height_above_floor_m, double min_weight,
                                              std::size_t max_new) {
  const auto pose_of = [&](const PlanCandidate& candidate) {
    PoseState pose;
    pose.x = candidate.x;
    pose.y = candidate.y;
    pose.z = candidate.floor_z + height_above_floor_m;
    pose.yaw = candidate.yaw;
    return pose;
  };
  std::vector<double> weights(particles.size());
  for (std::size_t i = 0; i < particles.size(); ++i) weights[i] = std::exp(particles[i].log_weight);
  // The weight each candidate holds: its particles, in_mode() of its pose.
  std::vector<double> held(candidates.size(), 0.0);
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const PoseState pose = pose_of(candidates[c]);
    for (std::size_t i = 0; i < particles.size(); ++i)
      if (in_mode(particles[i].state, pose, mode)) held[c] += weights[i];
  }
  std::vector<PlanCandidate> missing;
  for (std::size_t c = 0; c < candidates.size() && missing.size() < max_new; ++c) {
    if (held[c] >= min_weight) continue;
    // Distinct candidates may still be one hypothesis (a few degrees apart at one place).
    const PoseState pose = pose_of(candidates[c]);
    bool same = false;
    for (const PlanCandidate& taken : missing) same = same || in_mode(pose, pose_of(taken), mode);
    if (!same) missing.push_back(candidates[c]);
  }
  return missing;
}

}  // namespace conicloc::localizer
