#include "localizer/filter/localizer.hpp"

#include <cmath>
#include <limits>

#include "localizer/filter/deskew.hpp"
#include "localizer/filter/hypothesis_velocities.hpp"
#include "localizer/filter/pose_blur.hpp"
#include "localizer/filter/relative_motion.hpp"
#include "localizer/filter/search_rings.hpp"
#include "parallel/parallel_for.hpp"

namespace conicloc::localizer {

Localizer::Localizer(const maps::PlaneMap& map, const sensor::LaserCalibration& calibration,
                     const LocalizerConfig& config)
    : map_(map),
      config_(config),
      rng_(config.seed),
      threads_(resolve_thread_count(config.threads)),
      free_space_(map),
      wall_directions_(map_wall_directions(map, config.headings)),
      scan_turn_(config.scan_turn, threads_),
      see_through_history_(config.recovery.see_through_history),
      storey_twins_(map, free_space_, config.storey_twins) {
  motion_ = std::make_unique<MotionModel>(config_.motion, free_space_);
  filter_ = std::make_unique<ParticleFilter>(config_.filter, *motion_, free_space_);
  model_ = make_observation_model(config_.observation, map_, calibration);
  see_through_ = std::make_unique<SeeThroughCheck>(map_, calibration, config_.recovery.see_through,
                                                   config_.observation.sensor.max_range_m);
  for (int t = 0; t < threads_; ++t) scratches_.push_back(model_->make_scratch());
  if (config_.storey_twins.enabled && map_.storeys.size() > 1) {
    twin_model_ = make_observation_model(config_.observation, map_, calibration);
    for (int t = 0; t < threads_; ++t) twin_scratches_.push_back(twin_model_->make_scratch());
  }
}

Localizer::~Localizer() = default;

const char* status_name(LocalizerStatus status) {
  switch (status) {
    case LocalizerStatus::Tracking:
      return "tracking";
    case LocalizerStatus::Uncertain:
      return "uncertain";
    case LocalizerStatus::Lost:
      return "lost";
    case LocalizerStatus::Relocalizing:
      return "relocalizing";
  }
  return "uncertain";
}

void Localizer::reset_tracking_state() {
  last_time_s_.reset();
  scan_turn_.reset();
  last_turn_rad_.reset();
  last_estimate_.reset();
  last_estimate_step_.reset();
  last_good_pose_.reset();
  last_good_time_s_.reset();
  tilt_anchor_.reset();
  last_max_tempering_ = 0.0;
  last_rings_scored_ = 0;
  lost_count_ = 0;
  see_through_history_.clear();
  recoveries_since_checked_ = 0;
  relocalizing_ = false;
  converged_since_start_ = false;
  spread_by_restart_ = false;
  roughen_next_ = false;
  headings_from_next_scan_ = false;
  scans_since_plan_search_ = 0;
  storey_twins_.clear();
}

void Localizer::initialise(const Pose3& T_map_sensor, const Vector6& sigma) {
  const PoseState mean = pose_state_from(T_map_sensor);
  const int cell =
      free_space_.cell_at(mean.x, mean.y, mean.z - config_.motion.height_above_floor_m);
  if (cell >= 0) {
    const double floor_z =
        free_space_.floor_z_at(cell, mean.x, mean.y, mean.z - config_.motion.height_above_floor_m);
    motion_->set_height_above_floor(mean.z - floor_z);
  }
  filter_->initialise_at(mean, sigma, config_.filter.initial_particles, rng_);
  // A start the filter searches (wider than one tracked peak) is held at max_particles from its
  // first resampling on: drawn with fewer, that count would be copies of the first draws, their
  // poses and velocities, before any scan had told them apart.
  if (filter_->searching() && config_.filter.max_particles > config_.filter.initial_particles)
    filter_->initialise_at(mean, sigma, config_.filter.max_particles, rng_);
  reset_tracking_state();
  // The pose a user gives is the good pose a first recovery searches around.
  last_good_pose_ = mean;
}

void Localizer::initialise_global() {
  filter_->initialise_global(config_.filter.max_particles, rng_);
  // The plan's fields are built here rather than in the first scan's update, whose time a robot
  // waits on (a large building's take a fraction of a second).
  if (config_.plan_search.fraction > 0.0) build_plan_search();
  reset_tracking_state();
  spread_by_restart_ = true;
  headings_from_next_scan_ = true;
}

Eigen::Vector3d Localizer::mean_velocity() const {
  double mass = 0.0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Particle& p : filter_->particles()) {
    const double weight = std::exp(p.log_weight);
    mass += weight;
    sum += weight * Eigen::Vector3d(p.velocity_x, p.velocity_y, p.yaw_rate);
  }
  return mass > 0.0 ? Eigen::Vector3d(sum / mass) : Eigen::Vector3d::Zero();
}

std::optional<MeasuredTurn> Localizer::measure_turn(const sensor::Scan& scan,
                                                    const Eigen::Vector3d& velocity, double dt_s) {
  // The expected translation since the previous scan, in its frame: the estimate's last step,
  // else the cloud's mean velocity.
  Eigen::Vector2d expected = velocity.head<2>() * dt_s;
  if (last_estimate_step_ && last_estimate_step_->second > 0.0)
    expected =
        last_estimate_step_->first.translation().head<2>() * (dt_s / last_estimate_step_->second);
  std::optional<double> measured = scan_turn_.update(scan, expected);
  // Only between consecutive rotations: over a gap the turn may exceed the search, and a
  // rotation's turn over a much shorter step (a partial scan) is no turn rate.
  const ScanTurnConfig& limits = config_.scan_turn;
  if (!(dt_s >= limits.min_scan_step_s && dt_s <= limits.max_scan_step_s) ||
      (measured && !std::isfinite(*measured)))
    measured.reset();
  const std::optional<double> previous = last_turn_rad_;
  last_turn_rad_ = measured;
  if (!measured) return std::nullopt;
  const ScanTurn::Turn end = ScanTurn::end_to_end(*measured, previous, limits.sigma_rad);
  return MeasuredTurn{end.yaw_rad, end.sigma_rad};
}

Localizer::Prediction Localizer::predict(const sensor::Scan& scan,
                                         const std::optional<Pose3>& motion) {
  Prediction prediction;
  const double dt_s = last_time_s_ ? std::max(scan.end_time_s - *last_time_s_, 0.0) : 0.0;
  prediction.dt_s = dt_s;
  if (roughen_next_) filter_->roughen(rng_);
  roughen_next_ = false;
  if (motion) {
    motion_->predict(filter_->particles(), *motion, dt_s, rng_);
    // Odometry may stop (its file ends): the scan turn then starts afresh from here, and the
    // particles' velocities from the odometry's.
    scan_turn_.reset();
    last_turn_rad_.reset();
    if (dt_s > 0.0) {
      for (Particle& p : filter_->particles()) {
        p.velocity_x = motion->translation().x() / dt_s;
        p.velocity_y = motion->translation().y() / dt_s;
        p.velocity_variance = 0.0;
        p.yaw_rate = yaw_of(*motion) / dt_s;
      }
    }
    prediction.T_prev_curr = *motion;
    return prediction;
  }
  // Without odometry each particle moves by its own velocity, turned by what the scans measured
  // where they show it; the scan is de-skewed by the cloud's mean motion, the planar step
  // (dx, dy, dyaw) a tracked cloud's particles take. While a (re)start's cloud searches, that is
  // a mean over its places (de-skewing by its heaviest mode's velocity instead: 57 of 60
  // global starts and kidnaps settled against 56, within what the random stream moves).
  Eigen::Vector3d velocity = mean_velocity();
  if (config_.measure_scan_turn) prediction.turn = measure_turn(scan, velocity, dt_s);
  if (prediction.turn) {
    velocity.z() = std::clamp(prediction.turn->yaw_rad / dt_s, -config_.motion.max_yaw_rate_rad_s,
                              config_.motion.max_yaw_rate_rad_s);
  }
  // A cloud spread by a (re)start holds several places, each a sensor moving at its own speed:
  // each reverts to its own mean velocity (hypothesis_velocities.hpp), a tracked one to the
  // cloud's.
  if (searching_the_building()) {
    const std::vector<Eigen::Vector3d> means = hypothesis_velocities(
        filter_->particles(), config_.filter.mode, config_.motion.velocity_hypotheses);
    motion_->predict_velocity(filter_->particles(), means, dt_s, rng_, prediction.turn);
  } else {
    motion_->predict_velocity(filter_->particles(), velocity, dt_s, rng_, prediction.turn);
  }
  prediction.T_prev_curr =
      make_pose(velocity.x() * dt_s, velocity.y() * dt_s, 0.0, velocity.z() * dt_s);
  return prediction;
}

void Localizer::recover(const sensor::Scan& scan) {
  const double time_s = scan.end_time_s;
  const RecoveryConfig& recovery = config_.recovery;
  RestartMix mix;
  mix.headings = HeadingProposal::from_scan(wall_directions_, scan, config_.headings);
  if (recoveries_since_checked_ == 0 && last_good_pose_) {  // set from initialise() on
    // First alarm since the filter last tracked a checked pose: the tracked hypothesis stays,
    // most of the new particles go where the sensor can have got to since the last good pose.
    mix.keep_fraction = recovery.keep_fraction;
    mix.local_fraction = recovery.local_fraction;
    mix.centre = *last_good_pose_;
    const double elapsed_s = last_good_time_s_ ? std::max(time_s - *last_good_time_s_, 0.0) : 0.0;
    mix.local_sigma_xy_m = recovery.local_sigma_xy_m + recovery.search_speed_m_s * elapsed_s;
    mix.local_sigma_yaw_rad = recovery.local_sigma_yaw_rad;
    mix.local_heading_fraction = recovery.local_heading_fraction;
  } else {
    mix.keep_fraction = recovery.keep_fraction_global;
  }
  const std::size_t first_global = filter_->restart(config_.filter.max_particles, mix, rng_);
  draw_about_plan_candidates(scan, mix.headings, first_global);
  scans_since_plan_search_ = 0;
  ++recoveries_since_checked_;
  relocalizing_ = true;
  spread_by_restart_ = true;
  storey_twins_.clear();
}

void Localizer::build_plan_search() {
  if (!plan_search_)
    plan_search_ = std::make_unique<PlanSearch>(
        map_, free_space_, motion_->config().height_above_floor_m, config_.plan_search);
}

void Localizer::draw_about_plan_candidates(const sensor::Scan& scan,
                                           const HeadingProposal& headings, std::size_t first) {
  const PlanSearchConfig& plan = config_.plan_search;
  const std::size_t end = filter_->particles().size();
  if (!(plan.fraction > 0.0) || first >= end) return;
  build_plan_search();
  const std::vector<PlanCandidate> candidates =
      plan_search_->search(scan, headings.headings(), config_.threads);
  // A set drawn wholly about the candidates takes what they need: the share each would have at
  // the most candidates the search gives (--particles over max_candidates, 78 by default) times
  // their number, within [min_particles, the set's count]. One place the scan fits is a tracked
  // start's 200 particles, not 5,000 copies of it; the cost of the first scans follows how many
  // places the scan fits, not the particle budget.
  if (first == 0 && plan.fraction >= 1.0 && !candidates.empty()) {
    const std::size_t per_candidate = std::max<std::size_t>(
        config_.filter.max_particles / std::max<std::size_t>(plan.max_candidates, 1), 1);
    const std::size_t needed = std::clamp(candidates.size() * per_candidate,
                                          std::min(config_.filter.min_particles, end), end);
    filter_->particles().resize(needed);
  }
  const std::size_t size = filter_->particles().size();
  const auto count = static_cast<std::size_t>(
      std::floor(std::min(plan.fraction, 1.0) * static_cast<double>(size - first)));
  filter_->draw_about(candidates, first, count, plan.sigma_xy_m, plan.sigma_yaw_rad, rng_);
}

std::size_t Localizer::add_missing_hypotheses(const sensor::Scan& scan) {
  const MissingHypothesesConfig& missing = config_.missing_hypotheses;
  const PlanSearchConfig& plan = config_.plan_search;
  if (!(plan.fraction > 0.0) || missing.every_scans <= 0 || missing.max_new == 0) return 0;
  if (++scans_since_plan_search_ < missing.every_scans) return 0;
  scans_since_plan_search_ = 0;
  // A share of the configured count, not of the set's, and none while earlier additions have
  // not been resampled away yet (a searching cloud's weights are held near the ESS that
  // triggers resampling, so several additions could pile up).
  const double max_count = static_cast<double>(config_.filter.max_particles);
  if (static_cast<double>(filter_->particles().size()) >= (1.0 + missing.fraction) * max_count)
    return 0;
  build_plan_search();
  const HeadingProposal headings =
      HeadingProposal::from_scan(wall_directions_, scan, config_.headings);
  const std::vector<PlanCandidate> added = missing_hypotheses(
      filter_->particles(), plan_search_->search(scan, headings.headings(), config_.threads),
      config_.filter.mode, motion_->config().height_above_floor_m,
      config_.filter.runner_ups.min_weight, missing.max_new);
  const auto share = static_cast<std::size_t>(missing.fraction * max_count);
  const std::size_t each = added.empty() ? 0 : std::max<std::size_t>(share / added.size(), 1);
  filter_->add_hypotheses(added, each, plan.sigma_xy_m, plan.sigma_yaw_rad, rng_);
  return added.size();
}

std::optional<Particle> Localizer::moved_anchor(const Pose3& T_prev_curr) const {
  if (!tilt_anchor_) return std::nullopt;
  // The previous scan's best particle, carried by the cloud's planar motion; z follows its floor.
  Particle anchor = *tilt_anchor_;
  const PoseState moved = pose_state_from(anchor.state.to_pose() * T_prev_curr);
  anchor.state.x = moved.x;
  anchor.state.y = moved.y;
  anchor.state.yaw = moved.yaw;
  motion_->follow_floor(anchor);
  return anchor;
}

void Localizer::weigh_terms(const std::optional<Particle>& moved, bool levelled) {
  std::optional<Pose3> reference;
  if (moved) {
    PoseState state = moved->state;
    if (levelled) {  // level_to_scan gave every particle one tilt, the one it measured
      state.roll = filter_->particles().front().state.roll;
      state.pitch = filter_->particles().front().state.pitch;
    }
    reference = state.to_pose();
  } else if (last_good_pose_) {
    reference = last_good_pose_->to_pose();
  }
  if (reference)
    model_->weigh_terms(*reference, scratches_.empty() ? nullptr : scratches_.front().get());
}

std::optional<std::pair<double, double>> Localizer::level_to_scan(const Particle& anchor) {
  ObservationModel::Scratch* scratch = scratches_.empty() ? nullptr : scratches_.front().get();
  const MotionModelConfig& mounting = motion_->config();
  const auto tilt =
      measure_tilt(anchor.state, mounting.roll_rad, mounting.pitch_rad, config_.scan_tilt,
                   [&](const PoseState& state) { return model_->score(state.to_pose(), scratch); });

  if (!tilt) return std::nullopt;  // the pose does not explain the scan: the mounting model holds
  // A new tilt where it explains the scan significantly better, else the one the cloud held.
  const double gain_nats =
      last_max_tempering_ * (tilt->score.log_likelihood - tilt->start_log_likelihood);
  const bool better = gain_nats >= config_.scan_tilt.min_gain_nats;
  motion_->level_to(filter_->particles(), better ? tilt->roll_rad : anchor.state.roll,
                    better ? tilt->pitch_rad : anchor.state.pitch);
  // What the scan tells of the tilt, σ² = 1 / (τ·curvature), at most the search's bound.
  const double max_variance = config_.scan_tilt.max_tilt_rad * config_.scan_tilt.max_tilt_rad;
  const auto variance = [&](double curvature) {
    const double information = last_max_tempering_ * curvature;
    return information > 1.0 / max_variance ? 1.0 / information : max_variance;
  };
  return std::make_pair(variance(tilt->roll_curvature), variance(tilt->pitch_curvature));
}

bool Localizer::converged(const PoseEstimate& estimate) const {
  const StatusConfig& status = config_.status;
  const double spread_m = std::sqrt(std::max(estimate.covariance.diagonal().head<3>().sum(), 0.0));
  return spread_m <= status.converged_spread_m &&
         estimate.covariance(5, 5) <= status.converged_yaw_rad * status.converged_yaw_rad &&
         estimate.mode_weight >= status.converged_mode_weight;
}

StoreyTwinsUpdate Localizer::weigh_storey_twins(const sensor::Scan& scan, const PoseState& estimate,
                                                double tempering) {
  const auto score = [&](const std::vector<PoseState>& poses) {
    // One preparation for all of them, so that each is scored with the same terms.
    Eigen::AlignedBox3d box;
    for (const PoseState& pose : poses) box.extend(Eigen::Vector3d(pose.x, pose.y, pose.z));
    twin_model_->prepare(scan, box);
    std::vector<double> log_likelihoods(poses.size());
    parallel_for(poses.size(), threads_, [&](std::size_t begin, std::size_t end, int worker) {
      ObservationModel::Scratch* scratch = twin_scratches_[static_cast<std::size_t>(worker)].get();
      for (std::size_t i = begin; i < end; ++i)
        log_likelihoods[i] = twin_model_->score(poses[i].to_pose(), scratch).log_likelihood;
    });
    return log_likelihoods;
  };
  StoreyTwinsUpdate update =
      storey_twins_.update(estimate, motion_->config().height_above_floor_m, tempering, score);
  if (update.move_z_m) move_to_storey(*update.move_z_m);
  return update;
}

void Localizer::move_to_storey(double dz_m) {
  const auto move = [&](Particle& particle) {
    particle.state.z += dz_m;
    particle.cell = -1;  // the cell found afresh, on the new storey
    motion_->update_cell(particle);
  };
  for (Particle& particle : filter_->particles()) move(particle);
  if (tilt_anchor_) move(*tilt_anchor_);
  if (last_good_pose_) last_good_pose_->z += dz_m;
}

LocalizerStatus Localizer::status_of(const UpdateResult& result, bool converged) const {
  if (result.recovered) return LocalizerStatus::Lost;
  if (relocalizing_) return LocalizerStatus::Relocalizing;
  if (!converged || lost_count_ > 0) return LocalizerStatus::Uncertain;
  return LocalizerStatus::Tracking;
}

SeeThroughResult Localizer::see_through(const sensor::Scan& deskewed, const Pose3& T_map_sensor) {
  // One full prediction, its rings shared out: on one thread, the other threads would wait.
  see_through_->start(T_map_sensor, threads_, see_through_work_);
  parallel_for(static_cast<std::size_t>(threads_), threads_,
               [&](std::size_t begin, std::size_t end, int) {
                 for (std::size_t s = begin; s < end; ++s) {
                   see_through_->part(deskewed, static_cast<int>(s), see_through_work_);
                 }
               });
  return see_through_->result(see_through_work_);
}

bool Localizer::fails_lost_test(const WeightSummary& summary, const sensor::Scan& deskewed,
                                const Pose3& best_pose, UpdateResult& result) {
  const RecoveryConfig& recovery = config_.recovery;
  result.see_through_fraction = see_through(deskewed, result.pose).fraction();
  // A confident cloud is tested at its estimate. A tracked cloud that widened (no odometry, a
  // wrong pose whose walls only half fit) has no sharp estimate; its best fit to this scan is
  // one: when even that sees through the walls, no pose near the cloud explains the scan. A
  // cloud that has not converged since a (re)start or a wide initial pose is judged by its
  // inlier fraction alone: its best particle is any one of many candidates.
  std::optional<double> tested;
  if (result.spread_m < recovery.confident_spread_m) {
    tested = result.see_through_fraction;
  } else if (converged_since_start_ && !spread_by_restart_) {
    tested = see_through(deskewed, best_pose).fraction();
  }
  if (tested) {
    see_through_history_.add(deskewed.end_time_s, *tested);
  } else {
    see_through_history_.clear();
  }
  // Checked: given by the user (initialise) or clean since the last restart.
  const bool checked = recoveries_since_checked_ == 0 && last_good_pose_.has_value();
  const bool sees_through = tested && (*tested > recovery.max_see_through_fraction ||
                                       see_through_history_.sees_through(checked));
  return summary.all_minus_infinity ||
         summary.best_inlier_fraction < recovery.min_inlier_fraction || sees_through;
}

UpdateResult Localizer::update(const sensor::Scan& scan, const std::optional<Pose3>& motion) {
  const auto start = std::chrono::steady_clock::now();
  UpdateResult result;
  result.time_s = scan.end_time_s;

  // 1. Predict: move the particles by odometry or by their own velocities.
  const Prediction prediction = predict(scan, motion);
  const double dt_s = prediction.dt_s;
  const Pose3& T_prev_curr = prediction.T_prev_curr;
  if (prediction.turn) result.scan_turn_rad = prediction.turn->yaw_rad;
  if (config_.deskew)
    deskew_scan_into(scan, T_prev_curr, dt_s, scan.end_time_s, threads_, deskew_buffer_);
  const sensor::Scan& deskewed = config_.deskew ? deskew_buffer_ : scan;
  // Returns stay on their rings, so a climb during the scan (a stair) stays in it: the scan is
  // seen from below the end pose, by about half the climb of the floor under each particle.
  const double climb_fraction = mean_return_time_fraction(scan, dt_s, scan.end_time_s);
  if (headings_from_next_scan_) {
    const HeadingProposal headings =
        HeadingProposal::from_scan(wall_directions_, deskewed, config_.headings);
    // The first scan after initialise_global(): its particles still stand in its groups.
    filter_->draw_headings(headings, config_.filter.headings_per_position, rng_);
    draw_about_plan_candidates(deskewed, headings, 0);
    headings_from_next_scan_ = false;
  } else if (searching_the_building()) {
    result.hypotheses_added = add_missing_hypotheses(deskewed);
  }

  // 2. Weight: score every particle against the scan, culled once for the whole cloud; a
  // searching cloud scores each particle for the poses it stands for (pose_blur.hpp).
  // The cloud's spacing, in range error at the scan's median range: how far apart its poses are.
  // Only a cloud spread by a (re)start has its leading hypotheses refined: there the particles
  // sample far more coarsely than the likelihood peak is wide. A tracked cloud that widened along
  // a corridor is dense, and its spread is the real ambiguity that a climb would collapse.
  double spacing_m = 0.0;
  RefinementScale refinement;
  // The spacing costs a k-d tree over the cloud: measured only where the blur or a climb uses it.
  if ((config_.pose_blur || spread_by_restart_) && filter_->searching()) {
    refinement.range_m = median_range_m(deskewed);
    spacing_m = cloud_pose_blur_m(filter_->particles(), refinement.range_m);
    if (spread_by_restart_) refinement.step_m = spacing_m;
  }
  result.pose_blur_m = config_.pose_blur ? spacing_m : 0.0;
  model_->set_pose_blur(result.pose_blur_m);
  // A searching cloud scores a few rings (search_rings.hpp) with a model whose cost follows them.
  const bool searching_building = searching_the_building();
  const std::vector<int> scored =
      spread_rings(deskewed.rings.size(),
                   searching_building && model_->cost_follows_rings() ? config_.search_rings : 0);
  result.rings_scored = scored.size();
  // The tempering of a scan scored on other rings says nothing of this one's tilt evidence.
  if (scored.size() != last_rings_scored_) last_max_tempering_ = 0.0;
  last_rings_scored_ = scored.size();
  if (scored.size() < deskewed.rings.size()) {
    model_->prepare(keep_rings(deskewed, scored), filter_->position_bounds());
  } else {
    model_->prepare(deskewed, filter_->position_bounds());
  }
  result.terms = model_->term_count();
  WeightSummary summary;
  Pose3 best_pose = Pose3::Identity();  ///< this scan's best particle, before resampling
  const bool observed = result.terms > 0 && !filter_->particles().empty();
  std::optional<std::pair<double, double>> tilt_variance;
  if (observed) {
    // One tilt for the whole cloud, measured at its best particle: not while a (re)start's cloud
    // searches the building, whose best particle is often a look-alike, and the tilt that fits it
    // best would be forced onto the true hypothesis too. A cloud about a given or tracked pose is
    // one hypothesis however wide: a hand-held sensor's sway left level there took the true
    // pose's inliers under the lost test's bound before the start had settled (PNU seed 4).
    const std::optional<Particle> moved =
        searching_building ? std::nullopt : moved_anchor(T_prev_curr);
    if (moved) tilt_variance = level_to_scan(*moved);
    // Terms raised where the surfaces facing a direction hold few of them (weigh_terms), seen
    // from where the cloud stands: the previous best particle carried by the motion, at the tilt
    // just measured (under one exponent, as the tilt was tuned), or the given pose at a start.
    // Not while the cloud searches the building: its particles see different surfaces.
    if (config_.surface_weights && !searching_building)
      weigh_terms(moved, tilt_variance.has_value());
    summary = filter_->weight(*model_, scratches_, climb_fraction, refinement);
    tilt_anchor_ = filter_->particles()[summary.best];
    best_pose = tilt_anchor_->state.to_pose();
    result.effective_terms = summary.effective_terms;
    result.log_likelihood = summary.best_log_likelihood;
    result.inlier_fraction = summary.best_inlier_fraction;
    result.ess = summary.ess;
    result.tempering = summary.tempering;
    last_max_tempering_ = summary.max_tempering;
  } else {
    result.ess = static_cast<double>(filter_->particles().size());
  }

  // 3. Estimate, from the weighted set: after a resampling every weight is equal, and the
  // "heaviest particle" that anchors the strongest mode would be an arbitrary one (a cloud with
  // two modes then flips between them from scan to scan).
  const PoseEstimate estimate =
      estimate_pose(filter_->particles(), config_.estimate,
                    spread_by_restart_ ? ModeAnchor::MostWeight : ModeAnchor::HeaviestParticle);
  result.pose = estimate.state.to_pose();
  result.covariance = estimate.covariance;
  // The particles share one measured tilt: its uncertainty is the measurement's.
  if (tilt_variance) {
    result.covariance(3, 3) += tilt_variance->first;
    result.covariance(4, 4) += tilt_variance->second;
  }
  result.mode_weight = estimate.mode_weight;

  // 4. Resample when the weights have degenerated (KLD-adaptive count). A (re)start's cloud that
  // has not converged yet keeps its runner-up modes alive (runner_up_hypotheses.hpp): the scans
  // that tell a look-alike from the truth may come only after the cloud settled on one of them.
  result.resampled = filter_->resample_if_needed(rng_, spread_by_restart_);
  // Roughening jitters by a share of the cloud's extent (ParticleFilter::roughen): the width of
  // one mode in a cloud that holds one. A restart's cloud holds many, its extent is the distance
  // between them (PNU: 200 m, 1.2 m of jitter), and every resampling would blow each
  // mode apart — the truth's peak, a few cm wide, lost to a corridor along which the jitter
  // costs nothing. There the motion's own noise spreads the copies.
  roughen_next_ = result.resampled && !searching_the_building();

  result.spread_m = std::sqrt(std::max(estimate.covariance(0, 0) + estimate.covariance(1, 1), 0.0));

  // Recovery: a filter that fails the lost test for several scans (or explains nothing at all)
  // is lost; the set is refilled for the next scan, near the last good pose first (recover()).
  if (observed) {
    lost_count_ = fails_lost_test(summary, deskewed, best_pose, result) ? lost_count_ + 1 : 0;
    if (summary.all_minus_infinity || lost_count_ >= config_.recovery.lost_scans) {
      recover(deskewed);
      result.recovered = true;
      roughen_next_ = false;
      lost_count_ = 0;
      see_through_history_.clear();
    }
  }
  const bool is_converged = converged(estimate);
  const bool settled = !result.recovered && lost_count_ == 0 && is_converged;
  // A (re)start's cloud settles on one storey: the others stand as its twins from here on.
  if (settled && spread_by_restart_)
    storey_twins_.start(estimate.state, motion_->config().height_above_floor_m);
  // The twins' storeys in what the status and the covariance say (storey_twins.hpp). Weighed
  // with the scan unless there was none to weigh or the cloud was weighed on a few of its rings
  // (their τ_max is not the whole scan's).
  PoseEstimate reported = estimate;
  std::optional<double> moved_z_m;
  if (!result.recovered && !storey_twins_.empty() && twin_model_) {
    const StoreyTwinsUpdate twins =
        observed && scored.size() == deskewed.rings.size()
            ? weigh_storey_twins(deskewed, estimate.state, summary.max_tempering)
            : storey_twins_.current(estimate.state, motion_->config().height_above_floor_m);
    moved_z_m = twins.move_z_m;
    if (moved_z_m) {
      result.pose.translation().z() += *moved_z_m;
      reported.state.z += *moved_z_m;
    }
    // `reported` decides the status; the result's covariance holds the tilt's variance too.
    reported.covariance(2, 2) += twins.z_variance_m2;
    reported.mode_weight *= twins.estimate_share;
    result.covariance(2, 2) = reported.covariance(2, 2);
    result.mode_weight = reported.mode_weight;
    result.storey_share = twins.estimate_share;
    result.storey_twins = storey_twins_.twins().size();
  }
  if (settled) {
    converged_since_start_ = true;
    relocalizing_ = false;
    spread_by_restart_ = false;
    // Converged, explaining the scan, and checked against the walls for check_s: the pose a later
    // recovery searches around. A look-alike the cloud converged on after a restart sees through
    // a few per cent of its walls; were it trusted at once, its alarm would search around it
    // again, and the kept copy of it would win again. Nor is a storey the twins still doubt.
    if (see_through_history_.clean() && converged(reported)) {
      recoveries_since_checked_ = 0;
      last_good_pose_ = reported.state;
      last_good_time_s_ = scan.end_time_s;
    }
  }
  result.status = status_of(result, converged(reported));
  // The step ScanTurn expects next is the sensor's, not a move between storeys.
  if (last_estimate_ && dt_s > 0.0 && !result.recovered && !moved_z_m) {
    last_estimate_step_ = std::make_pair(Pose3(last_estimate_->inverse() * result.pose), dt_s);
  } else {
    last_estimate_step_.reset();
  }
  last_estimate_ = result.pose;
  result.particles = filter_->particles().size();
  last_time_s_ = scan.end_time_s;
  result.run_time_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace conicloc::localizer
