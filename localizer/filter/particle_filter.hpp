#pragma once
// The mechanics of the particle filter: initialisation, log-domain weighting (parallel over
// particles), low-variance resampling with a KLD-adaptive count, roughening and global
// injection. The algorithm's order lives in Localizer::update(); this class holds the set.

#include <random>

#include "localizer/filter/free_space.hpp"
#include "localizer/filter/heading_proposal.hpp"
#include "localizer/filter/hypothesis_refinement.hpp"
#include "localizer/filter/motion_model.hpp"
#include "localizer/filter/particle.hpp"
#include "localizer/filter/plan_search.hpp"
#include "localizer/filter/pose_estimate.hpp"
#include "localizer/filter/resampling.hpp"
#include "localizer/filter/runner_up_hypotheses.hpp"
#include "localizer/models/observation_model.hpp"

namespace conicloc::localizer {

struct ParticleFilterConfig {
  std::size_t min_particles = 200;       ///< KLD lower bound
  std::size_t max_particles = 5000;      ///< KLD upper bound and the global initial count
  std::size_t initial_particles = 1000;  ///< count for initialisation from a pose
  /// A global start draws each position for this many particles, each with its own heading: the
  /// poses of one position differ only in yaw, so one prediction serves them all
  /// (yaw_shared_prediction.hpp), and a first scan over a large building costs about a prediction
  /// per position instead of one per particle. 1: a position per particle.
  std::size_t headings_per_position = 4;
  /// Exponent on the scan likelihood, p(z|x)^τ: beams are not independent (shared map errors,
  /// calibration, clutter), and without it a scan of thousands of beams collapses the cloud onto
  /// one particle (Thrun et al. 6.3.2). The exponent used is
  ///   τ = tempering · min(1, n_eff / terms),
  /// n_eff the independent terms the scan is worth (ObservationModel::effective_terms: its terms
  /// grouped by surface, correlated_terms.hpp), and at most `reference_terms` when that is > 0.
  double tempering = 1.0;
  double reference_terms = 0.0;
  /// Adaptive tempering (localizer/adaptive_tempering.hpp): the exponent of a scan is lowered
  /// below the τ above, as far as needed, to keep the conditional ESS of its weights at least this
  /// fraction of the particle count, so a cloud spread over the building (global start, recovery)
  /// is not collapsed by one scan; 0 always uses τ.
  double adaptive_ess_fraction = 0.5;
  /// ... applied while the cloud is spread: the std. dev. of the particles' positions
  /// (position_spread_m(), weighted) exceeds this. A converged tracking cloud spans a few cm of one
  /// likelihood peak; there the configured τ (with roughening after each resampling) is what
  /// tracking accuracy was tuned with. A spread cloud also keeps max_particles at resampling (KLD
  /// shrinks only a converged one).
  double adaptive_min_spread_m = 0.25;
  /// ... unless the heaviest mode (the particles within `mode` of the heaviest one) holds at
  /// least this share of the weight and is itself no wider: the cloud then holds one hypothesis,
  /// and what little weight lies elsewhere is discarded by the full τ within a few scans if it
  /// explains the scans worse (or takes over if it explains them better). Under the lowered
  /// exponent a far remnant of a few per cent kept the spread, and with it the search, alive
  /// for as long as it lasted (a kidnapped pose's kept particles, 25 m away after 14 s).
  double settled_mode_weight = 0.95;
  /// A cloud that is not searching is tempered adaptively too, to keep this fraction of its
  /// count effective (conditional ESS; 0: always the full τ). A scan whose likelihood peak is far
  /// narrower than the cloud's spacing leaves, under the full τ, one particle to stand for the
  /// pose: ESS 1.1 of 5,000 at the second scan of a start known to 0.2 m (KU, hand-held, seed 3).
  /// That one particle holds one value in every direction, also in those the scan does not see —
  /// along a corridor, its position and the velocity drawn with it — and the cloud ran away at
  /// that speed. Kept to 5 %, the scan narrows the cloud at most twentyfold; the rest of its
  /// evidence comes with the next scans, which see the same surfaces. It binds in tracking too:
  /// a hand-held cloud of 200 particles, spaced by the motion's noise, kept fewer than 10
  /// effective on two scans of three (KU, seed 3: median exponent 0.36 τ), and tracks better so
  /// (docs/results/robustness-tracking-floor.md).
  double tracking_ess_fraction = 0.05;
  PoseEstimateConfig mode;
  double resample_ess_fraction = 0.5;  ///< resample when ESS < this × particle count
  double kld_epsilon = 0.05;           ///< KLD error bound ε (Fox 2003)
  double kld_z_quantile = 2.326;       ///< z_{1−δ}, δ = 0.01
  KldBins kld_bins;
  /// Roughening (Gordon, Salmond & Smith 1993): after resampling, jitter x, y, yaw by
  /// σ_j = K·E_j·N^(−1/3), E_j the spread of dimension j; plus these floors.
  double roughening_k = 0.1;
  double roughening_min_xy_m = 0.002;
  double roughening_min_yaw_rad = 0.0005;
  /// While searching, the leading hypotheses climb onto their likelihood peaks before the scan
  /// weighs them (hypothesis_refinement.hpp).
  HypothesisRefinementConfig refinement;
  /// While a (re)start's cloud settles, its runner-up modes keep particles through resampling
  /// (runner_up_hypotheses.hpp).
  RunnerUpConfig runner_ups;
};

/// How a recovery refills the set (ParticleFilter::restart).
struct RestartMix {
  double keep_fraction = 0.0;   ///< drawn from the current set by weight
  double local_fraction = 0.0;  ///< around `centre` ...
  PoseState centre;
  double local_sigma_xy_m = 1.0;  ///< ... with these std. devs., on free floor
  double local_sigma_yaw_rad = 0.5;
  /// Headings of the global particles; the local ones take theirs from it with probability
  /// `local_heading_fraction`, else from the Gaussian about `centre` (a lost sensor may have
  /// turned as much as moved).
  HeadingProposal headings;
  double local_heading_fraction = 0.0;
};

/// What weighting found out about one scan.
struct WeightSummary {
  double best_log_likelihood = 0.0;  ///< un-tempered, of the best particle
  double best_inlier_fraction = 0.0;
  double ess = 0.0;                 ///< after weighting
  double tempering = 0.0;           ///< exponent applied to this scan's log-likelihoods
  double max_tempering = 0.0;       ///< the exponent τ for this scan's (effective) term count
  double effective_terms = 0.0;     ///< n_eff at the best particle (ObservationModel)
  bool all_minus_infinity = false;  ///< no particle could explain the scan (weights reset uniform)
  std::size_t best = 0;             ///< index of the best particle (before any resampling)
};

class ParticleFilter {
 public:
  ParticleFilter(const ParticleFilterConfig& config, const MotionModel& motion,
                 const FreeSpace& free_space)
      : config_(config), motion_(motion), free_space_(free_space) {}

  /// `count` particles around `mean` with independent Gaussian noise of std. dev. `sigma`
  /// (x, y, z, roll, pitch, yaw; metres and radians).
  void initialise_at(const PoseState& mean, const Vector6& sigma, std::size_t count,
                     std::mt19937_64& rng);

  /// `count` particles uniform over the free space of all navigable cells, on the floor at the
  /// mounting height: a position for each block of headings_per_position particles, their yaws a
  /// star evenly round the turn from a uniform offset (draw_headings). Leaves the set empty when
  /// the map has no free space.
  void initialise_global(std::size_t count, std::mt19937_64& rng);

  /// Draws every particle's heading anew from `headings` (a global start's first scan): each block
  /// of `per_position` consecutive particles, which initialise_global() put at one position, gets
  /// headings spread over it (HeadingProposal::draw_spread); 1 for a cloud of single particles.
  void draw_headings(const HeadingProposal& headings, std::size_t per_position,
                     std::mt19937_64& rng);

  /// Redraws particles [first, first + count) about `candidates` (the plan search's poses where
  /// the scan fits, plan_search.hpp), as many about each, with std. devs. `sigma_xy_m` and
  /// `sigma_yaw_rad`, on the candidate's floor; weights uniform. Nothing without candidates.
  void draw_about(const std::vector<PlanCandidate>& candidates, std::size_t first,
                  std::size_t count, double sigma_xy_m, double sigma_yaw_rad, std::mt19937_64& rng);

  /// Adds hypotheses the set lacks (missing_hypotheses.hpp): `particles_each` particles about
  /// each of `candidates` (as draw_about()), added to the set's N, each of the mean weight 1/N;
  /// the weights are then normalised again.
  void add_hypotheses(const std::vector<PlanCandidate>& candidates, std::size_t particles_each,
                      double sigma_xy_m, double sigma_yaw_rad, std::mt19937_64& rng);

  /// Adds τ·log p(scan | particle) to every log-weight (parallel over `threads`, one scratch per
  /// worker) and normalises. Deterministic for any thread count. A particle that climbed
  /// (floor_rise_m ≠ 0, a stair) is scored `climb_fraction` × floor_rise_m higher (map z): the
  /// height the scan was seen from on average (see mean_return_time_fraction()).
  /// The scan is tempered to what it is worth in independent terms (see `tempering`), seen from
  /// the particle that explains it best. While searching() and `scale.step_m` > 0, the leading
  /// hypotheses are first refined onto their likelihood peaks (config().refinement), moving
  /// those particles.
  WeightSummary weight(const ObservationModel& model,
                       std::vector<std::unique_ptr<ObservationModel::Scratch>>& scratches,
                       double climb_fraction = 0.0, const RefinementScale& scale = {});

  /// Low-variance resampling to a KLD-adaptive count when ESS < threshold; weights become
  /// uniform. With `keep_runner_ups`, each runner-up mode that would get fewer than
  /// config().runner_ups.min_particles is resampled on its own to that many, its copies weighted
  /// so that it keeps its share (runner_up_hypotheses.hpp); the rest as above. Returns true when
  /// it resampled.
  bool resample_if_needed(std::mt19937_64& rng, bool keep_runner_ups = false);

  /// Roughening jitter after a resampling (see ParticleFilterConfig), each kept runner-up
  /// hypothesis by its own extent (Particle::hypothesis).
  void roughen(std::mt19937_64& rng);

  /// Replaces `fraction` of the particles (evenly spread over the set) by global samples and
  /// makes the weights uniform: the recovery of a kidnapped or lost sensor.
  void inject_global(double fraction, std::mt19937_64& rng);

  /// Recovery of a filter found lost: `count` particles, of which `mix.keep_fraction` are drawn
  /// from the current set by weight (the tracked hypothesis stays alive, in case the lost test
  /// fired on a correct pose), `mix.local_fraction` around `mix.centre` (the last good pose) and
  /// the rest uniformly over the free space; weights uniform. Adaptive tempering then lets the
  /// new particles compete with the old mode over several scans instead of one. Returns the index
  /// of the first particle drawn over the whole building (they fill the set from there on).
  std::size_t restart(std::size_t count, const RestartMix& mix, std::mt19937_64& rng);

  /// Bounding box of the particle positions (for culling the map once for the whole cloud).
  Eigen::AlignedBox3d position_bounds() const;

  /// Std. dev. of the particles' positions (x, y and z) about their weighted mean (m): a cloud
  /// at one place on two storeys is spread, though its xy are one.
  double position_spread_m() const;
  /// The cloud is spread over more than one likelihood peak (a global start, a recovery, a
  /// featureless corridor): position_spread_m() > adaptive_min_spread_m, and no single tight mode
  /// holds settled_mode_weight of the weight.
  bool searching() const;

  ParticleSet& particles() { return particles_; }
  const ParticleSet& particles() const { return particles_; }
  const ParticleFilterConfig& config() const { return config_; }

 private:
  /// A particle about `candidate`, on its storey's free floor (draw_about()); `normal` is the
  /// caller's standard normal distribution (one per draw of many, as its values come in pairs).
  Particle particle_about(const PlanCandidate& candidate, double sigma_xy_m, double sigma_yaw_rad,
                          std::normal_distribution<double>& normal, std::mt19937_64& rng) const;
  Particle global_particle(std::mt19937_64& rng, const HeadingProposal& headings = {}) const;
  /// A particle near `mix.centre` over the free space, or a global one when 20 draws miss it.
  Particle local_particle(const RestartMix& mix, std::mt19937_64& rng) const;
  void set_uniform_weights();
  /// refine_hypothesis() on the leading_hypotheses(), in parallel; updates their scores.
  void refine_leaders(const ObservationModel& model,
                      std::vector<std::unique_ptr<ObservationModel::Scratch>>& scratches,
                      double climb_fraction, const RefinementScale& scale,
                      std::vector<ObservationScore>& scores);

  ParticleFilterConfig config_;
  const MotionModel& motion_;
  const FreeSpace& free_space_;
  ParticleSet particles_;
};

}  // namespace conicloc::localizer
