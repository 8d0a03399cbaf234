#include "localizer/localizer.hpp"

#include <cmath>
#include <limits>

#include "localizer/deskew.hpp"
#include "localizer/parallel_for.hpp"
#include "localizer/relative_motion.hpp"

namespace conicloc::localizer {

Localizer::Localizer(const maps::PlaneMap& map, const sensor::LaserCalibration& calibration,
                     const LocalizerConfig& config)
    : map_(map), config_(config), rng_(config.seed), free_space_(map) {
  motion_ = std::make_unique<MotionModel>(config_.motion, free_space_);
  filter_ = std::make_unique<ParticleFilter>(config_.filter, *motion_, free_space_);
  model_ = make_observation_model(config_.observation, map_, calibration);
  see_through_ = std::make_unique<SeeThroughCheck>(map_, calibration, config_.recovery.see_through);
  const int threads = resolve_thread_count(config_.threads);
  for (int t = 0; t < threads; ++t) scratches_.push_back(model_->make_scratch());
}

Localizer::~Localizer() = default;

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
  last_time_s_.reset();
  last_estimate_.reset();
  velocity_motion_ = Pose3::Identity();
  velocity_dt_s_ = 0.0;
  lost_count_ = 0;
  roughen_next_ = false;
}

void Localizer::initialise_global() {
  filter_->initialise_global(config_.filter.max_particles, rng_);
  last_time_s_.reset();
  last_estimate_.reset();
  velocity_motion_ = Pose3::Identity();
  velocity_dt_s_ = 0.0;
  lost_count_ = 0;
  roughen_next_ = false;
}

Pose3 Localizer::predict(const sensor::Scan& scan, const std::optional<Pose3>& motion,
                         double& dt_s) {
  dt_s = last_time_s_ ? std::max(scan.end_time_s - *last_time_s_, 0.0) : 0.0;
  Pose3 T_prev_curr = Pose3::Identity();
  if (motion) {
    T_prev_curr = *motion;
  } else if (velocity_dt_s_ > 0.0 && dt_s > 0.0) {
    T_prev_curr = scale_motion(velocity_motion_, dt_s / velocity_dt_s_);
  }
  if (roughen_next_) filter_->roughen(rng_);
  roughen_next_ = false;
  motion_->predict(filter_->particles(), T_prev_curr, dt_s, rng_);
  return T_prev_curr;
}

void Localizer::remember_velocity(const Pose3& estimate, double dt_s, bool jumped) {
  if (last_estimate_ && dt_s > 0.0 && !jumped) {
    const Pose3 delta = last_estimate_->inverse() * estimate;
    const bool plausible = delta.translation().norm() <= config_.max_speed_m_s * dt_s &&
                           std::abs(yaw_of(delta)) <= config_.max_yaw_rate_rad_s * dt_s;
    velocity_motion_ = plausible ? delta : Pose3::Identity();
    velocity_dt_s_ = dt_s;
  } else {
    velocity_motion_ = Pose3::Identity();
    velocity_dt_s_ = 0.0;
  }
  last_estimate_ = estimate;
}

UpdateResult Localizer::update(const sensor::Scan& scan, const std::optional<Pose3>& motion) {
  const auto start = std::chrono::steady_clock::now();
  UpdateResult result;
  result.time_s = scan.end_time_s;

  // 1. Predict: move the particles by odometry or the constant-velocity guess.
  double dt_s = 0.0;
  const Pose3 T_prev_curr = predict(scan, motion, dt_s);
  const sensor::Scan deskewed =
      config_.deskew ? deskew_scan(scan, T_prev_curr, dt_s, scan.end_time_s) : scan;
  // Returns stay on their rings, so a climb during the scan (a stair) stays in it: the scan is
  // seen from below the end pose, by about half the climb of the floor under each particle.
  const double climb_fraction = mean_return_time_fraction(scan, dt_s, scan.end_time_s);

  // 2. Weight: score every particle against the scan, culled once for the whole cloud.
  model_->prepare(deskewed, filter_->position_bounds());
  result.terms = model_->term_count();
  WeightSummary summary;
  const bool observed = result.terms > 0 && !filter_->particles().empty();
  if (observed) {
    summary = filter_->weight(*model_, scratches_, climb_fraction);
    result.log_likelihood = summary.best_log_likelihood;
    result.inlier_fraction = summary.best_inlier_fraction;
    result.ess = summary.ess;
    result.tempering = summary.tempering;
  } else {
    result.ess = static_cast<double>(filter_->particles().size());
  }

  // 3. Estimate, from the weighted set: after a resampling every weight is equal, and the
  // "heaviest particle" that anchors the strongest mode would be an arbitrary one (a cloud with
  // two modes then flips between them from scan to scan).
  const PoseEstimate estimate = estimate_pose(filter_->particles(), config_.estimate);
  result.pose = estimate.state.to_pose();
  result.covariance = estimate.covariance;

  // 4. Resample when the weights have degenerated (KLD-adaptive count).
  result.resampled = filter_->resample_if_needed(rng_);
  roughen_next_ = result.resampled;

  result.spread_m = std::sqrt(std::max(estimate.covariance(0, 0) + estimate.covariance(1, 1), 0.0));

  // Recovery: a filter that explains too little, or that is confident of a pose through whose
  // walls the sensor sees, for several scans (or explains nothing at all) is lost; the set is
  // refilled with global particles for the next scan.
  if (observed) {
    result.see_through_fraction = see_through_->evaluate(deskewed, result.pose).fraction();
    const bool confident = result.spread_m < config_.recovery.confident_spread_m;
    const bool lost =
        summary.all_minus_infinity ||
        summary.best_inlier_fraction < config_.recovery.min_inlier_fraction ||
        (confident && result.see_through_fraction > config_.recovery.max_see_through_fraction);
    lost_count_ = lost ? lost_count_ + 1 : 0;
    if (summary.all_minus_infinity || lost_count_ >= config_.recovery.lost_scans) {
      filter_->restart_global(config_.filter.max_particles, config_.recovery.keep_fraction, rng_);
      result.recovered = true;
      roughen_next_ = false;
      lost_count_ = 0;
    }
  }
  result.particles = filter_->particles().size();
  remember_velocity(result.pose, dt_s, result.recovered);
  last_time_s_ = scan.end_time_s;
  result.run_time_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace conicloc::localizer
