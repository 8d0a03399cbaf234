#include "localizer/filter/hypothesis_refinement.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "localizer/filter/compass_search.hpp"

namespace conicloc::localizer {

std::vector<std::size_t> leading_hypotheses(const ParticleSet& particles,
                                            std::span<const ObservationScore> scores,
                                            const KldBins& bins, std::size_t count) {
  // Velocities do not make a hypothesis distinct: one pose with several velocities is one place.
  KldBins pose_bins = bins;
  pose_bins.velocity_m_s = std::numeric_limits<double>::infinity();
  std::unordered_map<std::uint64_t, std::size_t> best_in_bin;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (!std::isfinite(scores[i].log_likelihood)) continue;
    const auto [it, inserted] = best_in_bin.try_emplace(kld_bin_key(particles[i], pose_bins), i);
    if (!inserted && scores[i].log_likelihood > scores[it->second].log_likelihood) it->second = i;
  }
  std::vector<std::size_t> leaders;
  leaders.reserve(best_in_bin.size());
  for (const auto& [key, index] : best_in_bin) leaders.push_back(index);
  // Ties broken by index: the choice does not depend on the hash map's order.
  const auto better = [&](std::size_t a, std::size_t b) {
    return scores[a].log_likelihood > scores[b].log_likelihood ||
           (scores[a].log_likelihood == scores[b].log_likelihood && a < b);
  };
  const std::size_t kept = std::min(count, leaders.size());
  std::partial_sort(leaders.begin(), leaders.begin() + static_cast<std::ptrdiff_t>(kept),
                    leaders.end(), better);
  leaders.resize(kept);
  return leaders;
}

void refine_hypothesis(Particle& particle, ObservationScore& score, std::size_t index,
                       const RefinementScale& scale, const HypothesisRefinementConfig& config,
                       const CandidateScore& evaluate) {
  const double step_m = std::min(scale.step_m, config.max_step_m);
  const double range_m = std::max(scale.range_m, 1.0);
  // The particle stands for the poses around it, about one spacing wide: it climbs within twice
  // that, and leaves what lies beyond to the particles there.
  const double reach_m = 2.0 * step_m;
  const double start_x = particle.state.x;
  const double start_y = particle.state.y;
  // Axes x, y (step in metres) and yaw (the step turns a return at range_m as far).
  compass_search(
      3, step_m, config.min_step_m, config.max_evaluations, [&](std::size_t axis, double step) {
        Particle candidate = particle;
        if (axis == 0) candidate.state.x += step;
        if (axis == 1) candidate.state.y += step;
        const double turn = axis == 2 ? step / range_m : 0.0;
        candidate.state.yaw = std::remainder(candidate.state.yaw + turn, 2.0 * M_PI);
        if (std::hypot(candidate.state.x - start_x, candidate.state.y - start_y) > reach_m) {
          return Probe::Skipped;
        }
        const auto candidate_score = evaluate(index, candidate);
        if (!candidate_score || !(candidate_score->log_likelihood > score.log_likelihood))
          return Probe::Worse;
        particle = candidate;
        score = *candidate_score;
        return Probe::Improved;
      });
}

}  // namespace conicloc::localizer
