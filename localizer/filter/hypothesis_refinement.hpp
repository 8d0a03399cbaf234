#pragma once
// Hill-climbing the leading hypotheses of a searching cloud onto their likelihood peaks.
//
// Why: a scan's likelihood over the pose is a peak a few centimetres and a fraction of a degree
// wide, while a cloud spread over a building samples the poses decimetres apart. Whether a region
// explains the scan is told by its best pose, not by the particle that happens to stand in it: in
// the example building, measured on a kidnapped start, the true pose out-scored the wrong mode the
// filter converged to by ~550 nats on every scan (log p(z | x), conic-beam), but no particle stood
// close enough to the true peak to show it, and the look-alike mode, sampled more densely, won.
// So, while searching, the best particle of each of the `hypotheses` best distinct regions (KLD
// bins) climbs its own likelihood by a pattern search over (x, y, yaw) — the "improved proposal"
// idea of scan-matching particles (Grisetti, Stachniss & Burgard 2007), limited to the few
// particles that lead — and is scored at the peak it reached.

#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "localizer/filter/particle.hpp"
#include "localizer/filter/resampling.hpp"
#include "localizer/models/observation_model.hpp"

namespace conicloc::localizer {

struct HypothesisRefinementConfig {
  std::size_t hypotheses = 32;  ///< regions refined per scan while searching (0: off)
  double max_step_m = 0.5;      ///< first step of the pattern search, at most ...
  double min_step_m = 0.02;     ///< ... and the step at which it stops
  int max_evaluations = 40;     ///< likelihood evaluations per hypothesis
};

/// The scale of the search: first xy step (m), and the range (m) at which a yaw step moves a
/// return as far as the xy step does (yaw step = step / range_m).
struct RefinementScale {
  double step_m = 0.0;
  double range_m = 10.0;
};

/// Scores a candidate pose state of particle `index`; nullopt where the pose may not be taken
/// (off the navigable floor).
using CandidateScore =
    std::function<std::optional<ObservationScore>(std::size_t index, Particle& candidate)>;

/// Indices of the particles to refine: the best-scoring particle of each occupied bin of `bins`
/// (x, y, z, yaw), the `count` best of those, best first.
std::vector<std::size_t> leading_hypotheses(const ParticleSet& particles,
                                            std::span<const ObservationScore> scores,
                                            const KldBins& bins, std::size_t count);

/// Pattern search from `particle` (score `score`): probes ±step along x, y and ±step/range_m in
/// yaw, moves to any probe that scores higher, halves the step when none does, until the step is
/// below min_step_m or max_evaluations are spent; never farther than twice the first step from
/// where it started. Updates `particle` and `score` in place.
void refine_hypothesis(Particle& particle, ObservationScore& score, std::size_t index,
                       const RefinementScale& scale, const HypothesisRefinementConfig& config,
                       const CandidateScore& evaluate);

}  // namespace conicloc::localizer
