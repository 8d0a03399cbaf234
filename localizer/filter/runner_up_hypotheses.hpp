#pragma once
// The runner-up hypotheses of a cloud that is still choosing between places, kept alive through
// resampling.
//
// Why: resampling allocates particles in proportion to weight, so a hypothesis holding 0.1 % of
// a cloud resampled to 200 particles keeps none or one, and is gone by the next scan whatever
// the following scans would have said of it. That is right for a tracked cloud, where far weight
// is noise, but not for one that a global start or a recovery spread over the building and that
// is only now settling: there the leader is often a look-alike (a wing turned by 180°) that fits
// the first scans about as well as the truth, and the scans that tell them apart come later. In
// PNU (global start, seed 4), the true place held 0.6–2.4 % of the weight over the first second,
// 0.11 % when the cloud settled on the look-alike, then three particles, then none; from the
// tenth scan on the truth explains every scan 216–917 nats better, with nothing left to show it.
//
// So, while such a cloud settles, the runner-up modes holding at least `min_weight` of the
// probability (up to `max_runner_ups`, found around their heaviest particles, find_modes()) are
// resampled on their own, to at least `min_particles` each, each copy weighted W_k / n_k
// (importance weights: the represented distribution stays the same, only where the particles are
// spent changes). A runner-up dies when the scans push its weight under `min_weight`, and takes
// over when they favour it.
//
// Known costs: the kept copies add up to max_runner_ups × min_particles to the KLD count (the set
// may exceed max_particles by that), and a lone particle of a searching cloud over the floor is a
// mode too. Right after such a resampling the ESS is about the leader's count, half the set with
// four runner-ups kept, so the set is resampled on most scans until it converges.

#include <cstddef>
#include <vector>

#include "localizer/filter/particle.hpp"
#include "localizer/filter/pose_estimate.hpp"

namespace conicloc::localizer {

struct RunnerUpConfig {
  std::size_t max_runner_ups = 4;  ///< modes kept beside the leader (0: off)
  double min_weight = 1e-4;        ///< posterior probability under which a mode is dropped
  std::size_t min_particles = 50;  ///< particles each kept mode holds at least
};

/// Modes of a weighted cloud, heaviest particle first: mode k gathers the particles not yet in
/// a mode that are in_mode() of the heaviest such particle. At most `max_modes`; stops at the
/// first mode lighter than `min_weight`.
struct Modes {
  std::vector<int> mode_of;    ///< per particle: its mode, or −1 in none
  std::vector<double> weight;  ///< per mode: its share of the weight (normalised weights)
};
Modes find_modes(const ParticleSet& particles, const PoseEstimateConfig& mode,
                 std::size_t max_modes, double min_weight);

}  // namespace conicloc::localizer
