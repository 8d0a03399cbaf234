#pragma once
// The localizer: a particle filter over the sensor pose T_map_sensor in a PlaneMap, one update per
// scan — predict (motion) → weight (observation model) → resample → estimate.

#include <chrono>
#include <limits>
#include <memory>
#include <optional>
#include <random>

#include "localizer/filter/free_space.hpp"
#include "localizer/filter/heading_proposal.hpp"
#include "localizer/filter/missing_hypotheses.hpp"
#include "localizer/filter/motion_model.hpp"
#include "localizer/filter/particle_filter.hpp"
#include "localizer/filter/plan_search.hpp"
#include "localizer/filter/pose_estimate.hpp"
#include "localizer/filter/scan_tilt.hpp"
#include "localizer/filter/scan_turn.hpp"
#include "localizer/filter/see_through_history.hpp"
#include "localizer/filter/storey_twins.hpp"
#include "localizer/models/observation_factory.hpp"
#include "localizer/models/see_through_check.hpp"

namespace conicloc::localizer {

struct RecoveryConfig {
  /// The filter is lost when the best particle explains less than this fraction of the scan's
  /// terms (its inlier fraction), or when more than `max_see_through_fraction` of the returns pass
  /// through surfaces the tested pose predicts (localizer/see_through_check.hpp): the estimate of
  /// a confident cloud (xy std. dev. below `confident_spread_m`: its estimate is sharp in the
  /// plane, which is what the see-through test needs), the best particle of a wider
  /// cloud that had converged (not one spread by a restart or started wide) ...
  double min_inlier_fraction = 0.2;
  // Correct poses reach ~5 % for a few scans in door passages (frames, the far side of the
  // opening); a kidnapped pose sees through ~30 %.
  double max_see_through_fraction = 0.08;
  double confident_spread_m = 0.5;
  int lost_scans = 3;  ///< ... for this many consecutive scans
  /// Then the set is refilled to the maximum particle count (ParticleFilter::restart): the first
  /// time, `keep_fraction` drawn from the current cloud (the lost test may have fired on a correct
  /// pose: a hypothesis that still explains the scans must not be thrown away), `local_fraction`
  /// around the last good pose (or the initial one), within local_sigma_xy_m plus search_speed_m_s
  /// for every second since it (where a lost sensor most likely is), and the rest over the whole
  /// building. Lost again
  /// before the filter converged, it restarts over the whole building, keeping
  /// `keep_fraction_global` (0: a kept copy of a sharp wrong mode out-scores freshly spread
  /// particles for many scans).
  double keep_fraction = 0.2;
  double local_fraction = 0.5;
  double local_sigma_xy_m = 1.0;
  double local_sigma_yaw_rad = 0.5;
  double search_speed_m_s = 1.5;
  double keep_fraction_global = 0.0;
  /// Share of the particles around the last good pose that take a heading from the scan's walls
  /// (heading_proposal.hpp) instead of one near the last good heading: a lost sensor may have
  /// been turned as well as moved.
  double local_heading_fraction = 0.5;
  SeeThroughConfig see_through;
  /// ... or when the tested pose sees through in three scans of four over seconds, which passages
  /// at a correct pose do not (see_through_history.hpp).
  SeeThroughHistoryConfig see_through_history;
};

/// What the filter knows, for a user or a robot to act on.
enum class LocalizerStatus {
  Tracking,      ///< one confident hypothesis: position std. dev. ≤ converged_spread_m, one mode
  Uncertain,     ///< spread or several modes (a global start, a featureless corridor), or the
                 ///< lost test fired on this scan but not yet for long enough
  Lost,          ///< the lost test held for lost_scans scans: the set was refilled this scan
  Relocalizing,  ///< since a recovery, until the filter has converged again
};

/// "tracking", "uncertain", "lost", "relocalizing".
const char* status_name(LocalizerStatus status);

struct StatusConfig {
  /// Std. dev. of the whole cloud's position, all modes included, in x, y and z: identical
  /// storeys hold one place at one xy, and only z shows that the cloud has not chosen between
  /// them (generated storeys, seeds 2–6: a global start's weight drifted onto one storey the
  /// scans did not tell apart, which was then tracked as certain).
  double converged_spread_m = 0.3;
  double converged_yaw_rad = 0.15;     ///< yaw std. dev.
  double converged_mode_weight = 0.8;  ///< share of the weight in the estimate's mode
};

struct LocalizerConfig {
  ObservationConfig observation;
  MotionModelConfig motion;
  ParticleFilterConfig filter;
  PoseEstimateConfig estimate;
  RecoveryConfig recovery;
  StatusConfig status;
  ScanTurnConfig scan_turn;
  /// Roll and pitch measured from each scan for the whole cloud (scan_tilt.hpp).
  ScanTiltConfig scan_tilt;
  /// The headings a global start and a recovery draw, read off the scan (heading_proposal.hpp).
  HeadingProposalConfig headings;
  /// Where in the whole plan the scan fits: the poses a global start, and every restart's share
  /// over the whole building, draw part of their particles about (plan_search.hpp).
  PlanSearchConfig plan_search;
  /// ... and, while such a cloud searches, the places later scans fit that the cloud does not hold
  /// (missing_hypotheses.hpp).
  MissingHypothesesConfig missing_hypotheses;
  /// Once a (re)start's cloud has converged, the estimate's copies on the other storeys, weighed
  /// with every scan as the estimate is, so that identical storeys stay `uncertain` until a scan
  /// tells them apart, and a storey the cloud drifted onto gives way to the one the scans favour
  /// (storey_twins.hpp).
  StoreyTwinsConfig storey_twins;
  /// Without odometry, turn the particles by the turn measured between consecutive scans
  /// (ScanTurn) rather than by their own yaw rates.
  bool measure_scan_turn = true;
  bool deskew = true;  ///< move every return to the scan's reference time
  /// Raise the terms of surfaces that face a direction the scan's one exponent shortchanges to
  /// what the surfaces facing it are worth (ObservationModel::weigh_terms, direction_term_weights
  /// in correlated_terms.hpp), seen from the previous scan's best particle carried by the motion
  /// (the given pose at a start); not while a (re)start's cloud searches the building. Under one
  /// exponent a surface's share of the scan follows its returns: in PNU's hall the end walls,
  /// 22 and 28 m away, counted less than one term, and a walker setting off was trailed along it
  /// (hand-held: 6.9 cm xy RMSE, 0.33 m at worst; 2.1 cm and 0.06 m raised);
  /// docs/results/robustness-surface-weights.md.
  bool surface_weights = true;
  /// While the cloud is searching (ParticleFilter::searching()), score each particle for the
  /// poses it stands for: the model's σ widened by the cloud's spacing (pose_blur.hpp).
  bool pose_blur = true;
  /// While a global start's or a recovery's cloud searches the building, the observation model
  /// scores only this many of the scan's rings, spread over the elevations (search_rings.hpp);
  /// 0: every ring.
  std::size_t search_rings = 4;
  int threads = 0;         ///< worker threads for weighting; 0 = all cores
  std::uint64_t seed = 1;  ///< seeds the filter's random generator: runs repeat exactly
};

/// The result of one update: the estimate at the scan's reference time (its end) and diagnostics.
struct UpdateResult {
  double time_s = 0.0;  ///< reference time of the pose: the scan's end time (device clock)
  Pose3 pose = Pose3::Identity();        ///< T_map_sensor
  Matrix6 covariance = Matrix6::Zero();  ///< over (x, y, z, roll, pitch, yaw)
  double ess = 0.0;                      ///< effective sample size after weighting
  std::size_t particles = 0;             ///< particle count after resampling
  double log_likelihood = 0.0;           ///< best particle's log p(scan | pose), un-tempered
  double inlier_fraction = 0.0;          ///< best particle's share of explained terms
  std::size_t terms = 0;                 ///< beams / points / segments scored
  double effective_terms = 0.0;  ///< what they are worth as independent terms (correlated_terms)
  double run_time_ms = 0.0;      ///< wall time of this update
  bool resampled = false;
  bool recovered = false;  ///< the set was refilled this scan (RecoveryConfig); status lost
  double tempering = 0.0;  ///< likelihood exponent applied (adaptive, ≤ the configured one)
  double spread_m = 0.0;   ///< xy std. dev. of the cloud about the estimate
  double see_through_fraction = 0.0;  ///< share of returns beyond the estimate's predicted surfaces
  double mode_weight = 0.0;           ///< share of the weight in the estimate's mode
  double pose_blur_m = 0.0;  ///< range error the cloud's spacing leaves (pose_blur.hpp); 0 tracking
  std::size_t hypotheses_added = 0;  ///< places added before weighting (missing_hypotheses.hpp)
  /// The scan's rings the model was given: all of them, or LocalizerConfig::search_rings while a
  /// (re)start's cloud searches the building with a model whose cost follows the rings.
  std::size_t rings_scored = 0;
  /// Turn since the previous scan measured from the scans (ScanTurn); NaN where none was.
  double scan_turn_rad = std::numeric_limits<double>::quiet_NaN();
  /// The estimate's storey's share against its twins on the other storeys (storey_twins.hpp):
  /// 1 without twins; mode_weight includes it.
  double storey_share = 1.0;
  std::size_t storey_twins = 0;  ///< other storeys the sensor may still stand on
  LocalizerStatus status = LocalizerStatus::Uncertain;
};

class Localizer {
 public:
  /// Keeps a reference to `map` (must outlive the localizer); `calibration` describes the
  /// sensor's rings. Throws std::invalid_argument for an unknown observation model name.
  Localizer(const maps::PlaneMap& map, const sensor::LaserCalibration& calibration,
            const LocalizerConfig& config);
  ~Localizer();

  /// Particles around `T_map_sensor` with std. dev. `sigma` over (x, y, z, roll, pitch, yaw):
  /// initial_particles of them, or max_particles when the cloud is wide enough to be searched
  /// (ParticleFilter::searching()).
  /// When the pose lies over a navigable cell, the mounting height above that cell's floor is
  /// taken from it (so z follows the storeys from there on).
  void initialise(const Pose3& T_map_sensor, const Vector6& sigma);

  /// Particles over the free space of all navigable cells (global localisation).
  void initialise_global();

  /// One filter step on a scan. `motion` is T_prev_curr, the sensor's motion since the previous
  /// scan's reference time (from odometry); without it every particle moves by its own velocity,
  /// which the filter estimates (MotionModel::predict_velocity).
  UpdateResult update(const sensor::Scan& scan, const std::optional<Pose3>& motion = std::nullopt);

  const ParticleSet& particles() const { return filter_->particles(); }
  /// Memory of the plan search's fields (0 before a global start or restart built them).
  std::size_t plan_search_bytes() const { return plan_search_ ? plan_search_->memory_bytes() : 0; }
  const ObservationModel& observation_model() const { return *model_; }
  const LocalizerConfig& config() const { return config_; }

 private:
  /// What the prediction step did: the motion the scan is de-skewed by, over dt_s since the
  /// previous scan, and the turn measured between the scans (ScanTurn; none with odometry).
  struct Prediction {
    Pose3 T_prev_curr = Pose3::Identity();
    double dt_s = 0.0;
    std::optional<MeasuredTurn> turn;
  };
  Prediction predict(const sensor::Scan& scan, const std::optional<Pose3>& motion);
  /// The turn since the previous scan where the scans show it sharply (ScanTurn), with the
  /// translation the cloud expects over dt_s; updates the scan-turn state.
  std::optional<MeasuredTurn> measure_turn(const sensor::Scan& scan,
                                           const Eigen::Vector3d& velocity, double dt_s);
  /// The weighted mean of the particles' velocities: forward, left (m/s), yaw rate (rad/s).
  Eigen::Vector3d mean_velocity() const;
  /// Measures the tilt from the prepared scan at `anchor` (the previous scan's best particle
  /// moved, moved_anchor), and gives it to every particle (scan_tilt.hpp). Returns the variances
  /// of roll and pitch it leaves; nothing where no tilt was measured.
  std::optional<std::pair<double, double>> level_to_scan(const Particle& anchor);
  /// The previous scan's best particle carried by `T_prev_curr`, on its floor; none before the
  /// first scan the cloud was scored on.
  std::optional<Particle> moved_anchor(const Pose3& T_prev_curr) const;
  /// The prepared scan's terms weighed at the `moved` anchor (LocalizerConfig::surface_weights),
  /// at the tilt level_to_scan gave the particles if it `levelled` them; at the last good pose
  /// where there is no anchor yet. Needs a non-empty cloud.
  void weigh_terms(const std::optional<Particle>& moved, bool levelled);
  /// The see-through check at T_map_sensor, its rings predicted on the localizer's threads.
  SeeThroughResult see_through(const sensor::Scan& deskewed, const Pose3& T_map_sensor);
  /// This scan's lost test (RecoveryConfig): the best particle explains too little, or the tested
  /// pose (the estimate of a confident cloud, the best particle `best_pose` of a wider tracked
  /// one) sees through the walls in this scan or persistently (SeeThroughHistory). Sets
  /// result.see_through_fraction (at the estimate).
  bool fails_lost_test(const WeightSummary& summary, const sensor::Scan& deskewed,
                       const Pose3& best_pose, UpdateResult& result);
  /// Refills the set after the lost test held (RecoveryConfig), with headings from `scan`.
  void recover(const sensor::Scan& scan);
  /// Redraws plan_search.fraction of particles [first, end) about the poses where `scan` fits the
  /// plan (PlanSearch, built on first use); nothing when the fraction is 0. A set drawn wholly
  /// about them (first 0, fraction 1) is first cut to the count their number needs.
  void draw_about_plan_candidates(const sensor::Scan& scan, const HeadingProposal& headings,
                                  std::size_t first);
  /// Every MissingHypothesesConfig::every_scans scans of a search, the places where `scan` fits
  /// the plan that the cloud lacks, added to it; returns how many.
  std::size_t add_missing_hypotheses(const sensor::Scan& scan);
  /// The plan search's fields, at the mounting height above each storey's floor, once.
  void build_plan_search();
  /// A global start's or a recovery's cloud still searching the building: its best particle may be
  /// a look-alike (no tilt taken from it) and its extent spans many modes (no roughening by it).
  bool searching_the_building() const { return spread_by_restart_ && filter_->searching(); }
  /// One confident hypothesis (StatusConfig).
  bool converged(const PoseEstimate& estimate) const;
  LocalizerStatus status_of(const UpdateResult& result, bool converged) const;
  /// This scan's evidence on the estimate's twins on the other storeys (storey_twins.hpp): the
  /// estimate and its twins scored with `scan` by twin_model_, on the localizer's threads. Moves
  /// the cloud to a twin that took it.
  StoreyTwinsUpdate weigh_storey_twins(const sensor::Scan& scan, const PoseState& estimate,
                                       double tempering);
  /// Every particle (and the poses kept of past scans) moved by `dz_m` onto another storey.
  void move_to_storey(double dz_m);
  void reset_tracking_state();

  const maps::PlaneMap& map_;
  LocalizerConfig config_;
  std::mt19937_64 rng_;
  int threads_ = 1;  ///< config_.threads resolved (0: all cores)
  FreeSpace free_space_;
  std::unique_ptr<MotionModel> motion_;
  std::unique_ptr<ParticleFilter> filter_;
  std::unique_ptr<ObservationModel> model_;
  std::unique_ptr<SeeThroughCheck> see_through_;
  SeeThroughWork see_through_work_;
  sensor::Scan deskew_buffer_;  ///< the scan being weighed, de-skewed (its storage kept)
  std::vector<std::unique_ptr<ObservationModel::Scratch>> scratches_;
  std::vector<double> wall_directions_;      ///< the map's dominant wall directions (headings)
  std::unique_ptr<PlanSearch> plan_search_;  ///< built by the first global start or restart
  /// A global start draws its headings from the first scan (initialise_global()).
  bool headings_from_next_scan_ = false;
  ScanTurn scan_turn_;                   ///< the motion between scans, for runs without odometry
  std::optional<double> last_turn_rad_;  ///< the last turn it measured
  /// The estimate's last step (in the frame of the estimate before it) and its duration: the
  /// translation ScanTurn expects next. The particles' mean velocity stands in before there is one
  /// (or after a recovery): a cloud collapsed on one particle has that particle's velocity.
  std::optional<Pose3> last_estimate_;
  std::optional<std::pair<Pose3, double>> last_estimate_step_;

  /// The last weighted scan's best particle (before resampling): where the next scan's tilt is
  /// measured from.
  std::optional<Particle> tilt_anchor_;
  /// What the previous scan was worth in independent terms (its τ_max; a searching cloud weighs
  /// it with less, which says how far the cloud may move, not what the scan shows of a tilt):
  /// what a tilt's gain and curvature are worth.
  double last_max_tempering_ = 0.0;
  std::size_t last_rings_scored_ = 0;  ///< of the previous scan: τ_max holds for that many rings

  std::optional<double> last_time_s_;
  /// The estimate at the last converged scan whose pose had been checked (SeeThroughHistory).
  std::optional<PoseState> last_good_pose_;
  std::optional<double> last_good_time_s_;  ///< unset: the pose was given, not tracked
  int lost_count_ = 0;
  SeeThroughHistory see_through_history_;  ///< of the poses the lost test examined
  StoreyTwins storey_twins_;               ///< started when a (re)start's cloud converges
  /// The model the twins are scored with: model_ is culled to what the cloud can see, which
  /// leaves out the other storeys (a twin scored there missed its own floor and walls). This one
  /// is culled to the box of the estimate and its twins. Made for maps of several storeys.
  std::unique_ptr<ObservationModel> twin_model_;
  std::vector<std::unique_ptr<ObservationModel::Scratch>> twin_scratches_;
  /// Recoveries since the estimate last passed the see-through history: the first one searches
  /// around the last good pose, later ones over the whole building.
  int recoveries_since_checked_ = 0;
  bool relocalizing_ = false;  ///< since a recovery, until the filter has converged again
  /// The cloud has converged since initialise() / initialise_global(): a wide cloud is then one
  /// that widened while tracking, not a wide start.
  bool converged_since_start_ = false;
  /// The cloud was spread by initialise_global() or a recovery and has not converged since.
  bool spread_by_restart_ = false;
  bool roughen_next_ = false;
  int scans_since_plan_search_ = 0;  ///< of a search, since the plan was last searched
};

}  // namespace conicloc::localizer
