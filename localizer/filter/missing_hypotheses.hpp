#pragma once
// The places a searching cloud does not hold but a later scan proposes.
//
// Why: a global start (or a recovery) draws its particles about the places where its first scan
// fits the floor plan (plan_search.hpp). That scan may not propose the true place: PNU, global
// start, seed 5 — the truth explains 148 of the first 150 scans better than the look-alike the
// cloud settled on (median 304 nats), yet no particle ever stood there. Searched again every
// half second, the plan proposed the truth in 13 of 17 searches, but ranked 22nd to 50th of 64
// (s = 0.37–0.42 against the best's 0.41–0.47): seen from above, at one height, the look-alikes
// fit as well. Only the 3D observation model tells them apart, so the plan does not choose; every
// candidate the cloud lacks is added, and the scan's weighting judges them with the rest.
//
// So while the cloud searches, the plan is searched again every `every_scans` scans, and a
// candidate is missing when the particles in_mode() of it carry less than RunnerUpConfig's
// `min_weight` of the probability (under that, runner_up_hypotheses.hpp drops a mode too). Two
// missing candidates in one mode are one hypothesis. Each enters as particles of the set's mean
// weight 1/N (the injection of augmented MCL, Thrun et al. 8.3.5: as likely as an average particle
// before the scan), added to the set rather than put in place of its lightest particles, which may
// be a kept runner-up's (PNU seed 3 lost its truth so). A wrong one falls under the floor within a
// scan or two and is not kept through resampling; the truth gains the weight a scan at a time.

#include <cstddef>
#include <vector>

#include "localizer/filter/particle.hpp"
#include "localizer/filter/plan_search.hpp"
#include "localizer/filter/pose_estimate.hpp"

namespace conicloc::localizer {

struct MissingHypothesesConfig {
  /// While a (re)start's cloud searches, the plan is searched again every this many scans (0:
  /// only on the scan that starts the search; `localize --repropose-every N`; nothing without
  /// the plan search, PlanSearchConfig::fraction 0). Off by default:
  /// over the five-seed global-start and kidnap sweeps (360 runs, with and without odometry),
  /// every 5 scans found the place within 10 s in 342 runs against 339 (PNU's global seed 5 and
  /// kidnap seeds 2 and 5 without odometry among the gains), within 10 cm in as many (324), but
  /// each added place keeps the cloud searching longer: PNU's global phase cost 2–6× per scan
  /// (the plan search itself ~45 ms there on 2 threads, the longer search the rest).
  int every_scans = 0;
  std::size_t max_new = 64;  ///< hypotheses added per search, best first
  /// Particles added, a share of the configured count, split evenly (≥ 1 each). A candidate is
  /// missing when the cloud holds less of it than RunnerUpConfig::min_weight.
  double fraction = 0.1;
};

/// The candidates (best first, as PlanSearch::search gives them) that `particles` (normalised
/// log-weights) hold less than `min_weight` of, one per mode, at most `max_new`, best first.
/// `height_above_floor_m` puts a candidate's pose at the sensor's height over its floor, to
/// compare with the particles'.
std::vector<PlanCandidate> missing_hypotheses(const ParticleSet& particles,
                                              const std::vector<PlanCandidate>& candidates,
                                              const PoseEstimateConfig& mode,
                                              double height_above_floor_m, double min_weight,
                                              std::size_t max_new);

}  // namespace conicloc::localizer
