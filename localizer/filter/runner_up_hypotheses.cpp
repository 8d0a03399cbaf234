#include "localizer/filter/runner_up_hypotheses.hpp"

#include <cmath>
#include <limits>

namespace conicloc::localizer {

Modes find_modes(const ParticleSet& particles, const PoseEstimateConfig& mode,
                 std::size_t max_modes, double min_weight) {
  Modes modes;
  modes.mode_of.assign(particles.size(), -1);
  while (modes.weight.size() < max_modes) {
    // The heaviest particle in no mode yet anchors the next one (ties: the earlier particle).
    std::size_t anchor = particles.size();
    double heaviest = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < particles.size(); ++i) {
      if (modes.mode_of[i] < 0 && particles[i].log_weight > heaviest) {
        heaviest = particles[i].log_weight;
        anchor = i;
      }
    }
    if (anchor == particles.size()) break;
    const int label = static_cast<int>(modes.weight.size());
    double weight = 0.0;
    for (std::size_t i = 0; i < particles.size(); ++i) {
      if (modes.mode_of[i] < 0 && in_mode(particles[i].state, particles[anchor].state, mode)) {
        modes.mode_of[i] = label;
        weight += std::exp(particles[i].log_weight);
      }
    }
    if (weight < min_weight) {
      for (int& of : modes.mode_of)
        if (of == label) of = -1;
      break;
    }
    modes.weight.push_back(weight);
  }
  return modes;
}

}  // namespace conicloc::localizer
