#include "localizer/filter/hypothesis_velocities.hpp"

#include <cmath>

#include "localizer/filter/runner_up_hypotheses.hpp"

namespace conicloc::localizer {

namespace {
Eigen::Vector3d velocity_of(const Particle& particle) {
  return {particle.velocity_x, particle.velocity_y, particle.yaw_rate};
}
}  // namespace

std::vector<Eigen::Vector3d> hypothesis_velocities(const ParticleSet& particles,
                                                   const PoseEstimateConfig& mode,
                                                   std::size_t max_modes) {
  const Modes modes = find_modes(particles, mode, max_modes, 0.0);
  std::vector<Eigen::Vector3d> sums(modes.weight.size(), Eigen::Vector3d::Zero());
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const int of = modes.mode_of[i];
    if (of >= 0) sums[of] += std::exp(particles[i].log_weight) * velocity_of(particles[i]);
  }
  std::vector<Eigen::Vector3d> means(particles.size());
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const int of = modes.mode_of[i];
    // A mode of weight 0 (every weight underflowed) has no mean: its particles keep their own.
    means[i] = of >= 0 && modes.weight[of] > 0.0 ? Eigen::Vector3d(sums[of] / modes.weight[of])
                                                 : velocity_of(particles[i]);
  }
  return means;
}

}  // namespace conicloc::localizer
