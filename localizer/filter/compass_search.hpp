#pragma once
// Compass search (a pattern search; Kolda, Lewis & Torczon 2003, "Optimization by direct search",
// SIAM Review 45(3)): probe ±step along each axis in turn, take every probe that scores higher,
// halve the step after a sweep with no gain. No gradient: the likelihoods it climbs are sums of
// mixtures with clipped tails, flat or kinked where a return changes surface.

#include <cstddef>

namespace conicloc::localizer {

/// What one probe did.
enum class Probe {
  Skipped,   ///< not evaluated (outside where the search may go): costs no evaluation
  Worse,     ///< evaluated, not higher: the search stays
  Improved,  ///< evaluated and higher: the caller moved to it
};

/// Sweeps the probes +step, −step along axes 0 … axes−1 (`probe(axis, signed_step)`), halving the
/// step after a sweep without an improvement, until it is below `min_step` or `max_evaluations`
/// probes have been evaluated. Returns the evaluations spent.
template <typename ProbeFunction>
int compass_search(std::size_t axes, double first_step, double min_step, int max_evaluations,
                   ProbeFunction&& probe) {
  double step = first_step;
  int evaluations = 0;
  while (step >= min_step && evaluations < max_evaluations) {
    bool improved = false;
    for (std::size_t axis = 0; axis < axes; ++axis) {
      for (const double signed_step : {step, -step}) {
        if (evaluations >= max_evaluations) break;
        const Probe result = probe(axis, signed_step);
        if (result != Probe::Skipped) ++evaluations;
        if (result == Probe::Improved) improved = true;
      }
    }
    if (!improved) step *= 0.5;
  }
  return evaluations;
}

}  // namespace conicloc::localizer
