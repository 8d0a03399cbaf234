#include "sim/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sim/smooth_path.hpp"

namespace conicloc::sim {
namespace {

double wrap_to_pi(double angle) {
  return std::remainder(angle, 2.0 * M_PI);
}

// A carrier whose heading is this far from the way it is to go turns on the spot first.
constexpr double kTurnInPlace_rad = 0.35;
// The carrier's yaw is integrated at this step (track_yaw()).
constexpr double kYawTrackStep_s = 0.005;
// The speed at the slowest corner (the yaw-rate limit's floor): never stall.
constexpr double kCrawl_mps = 0.05;

}  // namespace

Trajectory::Trajectory(const std::vector<Waypoint>& waypoints, const TrajectoryConfig& config,
                       std::mt19937_64& rng, const GroundHeightFunction& ground_height)
    : config_(config) {
  if (!(config_.yaw_acceleration_max_radps2 > 0.0) ||
      !std::isfinite(config_.yaw_acceleration_max_radps2))
    throw std::invalid_argument("trajectory: the yaw acceleration limit must be positive and finite");
  if (config_.sensor_height_m < 0.0) {
    config_.sensor_height_m = config_.style == MotionStyle::Robot ? 0.8 : 1.4;
  }
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (std::size_t i = 0; i < wander_frequency_hz_.size(); ++i) {
    wander_frequency_hz_[i] = 0.05 + 0.25 * unit(rng);
    wander_phase_rad_[i] = 2.0 * M_PI * unit(rng);
  }
  if (waypoints.empty()) return;
  TimedSample start;
  start.floor_point = on_ground(waypoints.front().floor_point, ground_height);
  samples_.push_back(start);
  // Legs end at waypoints with a yaw (stop and turn there) and at the last waypoint.
  std::vector<Eigen::Vector3d> leg{waypoints.front().floor_point};
  bool first_leg = true;
  auto finish_leg = [&](const std::optional<double>& yaw) {
    if (leg.size() >= 2) {
      const auto path = smooth_path(leg);
      if (path.size() >= 2) {
        if (first_leg && !waypoints.front().yaw_rad) {
          samples_.back().yaw_rad = path.front().heading_rad;  // start facing along the path
        }
        append_leg(leg, ground_height);
      }
    }
    first_leg = false;
    if (yaw) turn_to(*yaw);
    leg = {samples_.back().floor_point};
  };
  if (waypoints.front().yaw_rad) samples_.back().yaw_rad = *waypoints.front().yaw_rad;
  for (std::size_t i = 1; i < waypoints.size(); ++i) {
    leg.push_back(waypoints[i].floor_point);
    if (waypoints[i].yaw_rad || i + 1 == waypoints.size()) finish_leg(waypoints[i].yaw_rad);
  }
  track_yaw();
}

void Trajectory::track_yaw() {
  // The carrier turns toward the samples' yaw (the path's tangent, rate limited, and the turns on
  // the spot) as a base whose yaw rate changes by at most α per second: the samples' own rate as
  // feed-forward, plus the rate that closes the remaining error and can still brake to it,
  // √(2α|e|). Where the samples' yaw obeys the limit (the speed profile holds v²|Δκ|/ds ≤ α,
  // turns on the spot ramp at α) it is followed closely (its rate steps at each sample: within
  // 0.2° while driving on a zig-zag route); where it does not (a crawl through a
  // hairpin, the first steps of a route, the switch from driving to turning) the carrier lags a
  // little and catches up.
  yaw_track_.clear();
  if (samples_.empty()) return;
  const double alpha = config_.yaw_acceleration_max_radps2;
  const double omega_max = config_.yaw_rate_max_radps;
  const double duration = samples_.back().time_s;
  const auto steps = static_cast<std::size_t>(std::ceil(duration / kYawTrackStep_s));
  yaw_track_.reserve(steps + 1);
  double yaw = samples_.front().yaw_rad;
  double rate = 0.0;
  yaw_track_.push_back(yaw);
  double previous_target = yaw;
  for (std::size_t k = 1; k <= steps; ++k) {
    const double target = sample_at(static_cast<double>(k) * kYawTrackStep_s).yaw_rad;
    const double feed_forward = (target - previous_target) / kYawTrackStep_s;
    previous_target = target;
    const double error = target - (yaw + feed_forward * kYawTrackStep_s);
    const double closing =
        std::copysign(std::min(std::sqrt(2.0 * alpha * std::abs(error)),
                               std::abs(error) / kYawTrackStep_s),
                      error);
    const double wanted = std::clamp(feed_forward + closing, -omega_max, omega_max);
    rate = std::clamp(wanted, rate - alpha * kYawTrackStep_s, rate + alpha * kYawTrackStep_s);
    yaw += rate * kYawTrackStep_s;
    yaw_track_.push_back(yaw);
  }
}

double Trajectory::tracked_yaw(double time_s) const {
  if (yaw_track_.empty()) return sample_at(time_s).yaw_rad;
  const double position = std::clamp(time_s, 0.0, duration_s()) / kYawTrackStep_s;
  const auto k = std::min(static_cast<std::size_t>(position), yaw_track_.size() - 1);
  if (k + 1 >= yaw_track_.size()) return yaw_track_.back();
  const double w = position - static_cast<double>(k);
  return yaw_track_[k] + w * (yaw_track_[k + 1] - yaw_track_[k]);
}

void Trajectory::turn_to(double yaw_rad) {
  // A trapezoidal yaw-rate profile: speeding up at α to ω_max, turning, slowing down at α; a
  // turn shorter than ω_max²/α never reaches ω_max (a triangle of peak √(α|δ|)).
  TimedSample current = samples_.back();
  const double delta = wrap_to_pi(yaw_rad - current.yaw_rad);
  const double alpha = config_.yaw_acceleration_max_radps2;
  const double peak = std::min(config_.yaw_rate_max_radps, std::sqrt(alpha * std::abs(delta)));
  if (!(peak > 0.0)) return;
  const double ramp_s = peak / alpha;
  const double duration = std::abs(delta) / peak + ramp_s;
  // The angle turned after t: ½αt² on the ramp up, then ω t, then the ramp down mirrored.
  const auto turned = [&](double t) {
    if (t < ramp_s) return 0.5 * alpha * t * t;
    if (t > duration - ramp_s) {
      const double left = duration - t;
      return std::abs(delta) - 0.5 * alpha * left * left;
    }
    return 0.5 * peak * ramp_s + peak * (t - ramp_s);
  };
  const double step_s = 0.02;
  const int steps = static_cast<int>(std::ceil(duration / step_s));
  const double start_yaw = current.yaw_rad;
  const double start_time = current.time_s;
  for (int k = 1; k <= steps; ++k) {
    const double t = duration * k / steps;
    current.time_s = start_time + t;
    current.yaw_rad = start_yaw + std::copysign(turned(t), delta);
    current.speed_mps = 0.0;
    samples_.push_back(current);
  }
}

void Trajectory::append_leg(const std::vector<Eigen::Vector3d>& points,
                            const GroundHeightFunction& ground_height) {
  const auto path = smooth_path(points);
  const std::size_t n = path.size();
  // Speed limits: cruise, lateral acceleration v²κ ≤ a_lat, yaw rate vκ ≤ ω_max; then the
  // trapezoid: forward pass v_{i+1}² ≤ v_i² + 2a·ds (speeding up), backward pass (slowing down),
  // at rest at both ends.
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) {
    double limit = config_.speed_mps;
    const double kappa = std::abs(path[i].curvature);
    if (kappa > 1e-9) {
      limit = std::min({limit, std::sqrt(config_.lateral_acceleration_mps2 / kappa),
                        config_.yaw_rate_max_radps / kappa});
    }
    v[i] = std::max(limit, kCrawl_mps);
  }
  // Yaw acceleration: between samples ds apart whose signed curvatures differ by Δκ, the yaw rate
  // v·κ changes by v·Δκ in ds/v, so v²·|Δκ|/ds ≤ α (a bend that turns the other way at once, as
  // the path does at a waypoint between opposite bends, is driven slowly).
  for (std::size_t i = 1; i < n; ++i) {
    const double change = std::abs(path[i].curvature - path[i - 1].curvature);
    const double ds = path[i].s_m - path[i - 1].s_m;
    if (!(change > 1e-9) || !(ds > 0.0)) continue;
    const double limit =
        std::max(std::sqrt(config_.yaw_acceleration_max_radps2 * ds / change), kCrawl_mps);
    v[i] = std::min(v[i], limit);
    v[i - 1] = std::min(v[i - 1], limit);
  }
  v.front() = 0.0;
  v.back() = 0.0;
  // A corner sharper than kTurnInPlace_rad between two sample steps (a hairpin where the route
  // doubles back) is taken as a robot takes it: stop, turn on the spot to the next step, go on.
  // The yaw-rate limit above cannot slow the carrier for a corner a few centimetres long.
  std::vector<double> step_heading(n, 0.0);  // of the step from sample i − 1 to i
  for (std::size_t i = 1; i < n; ++i) {
    const Eigen::Vector3d step = path[i].position - path[i - 1].position;
    step_heading[i] = std::atan2(step.y(), step.x());
  }
  std::vector<bool> turn_before(n, false);
  for (std::size_t i = 2; i < n; ++i) {
    if (std::abs(wrap_to_pi(step_heading[i] - step_heading[i - 1])) > kTurnInPlace_rad) {
      turn_before[i] = true;
      v[i - 1] = 0.0;
    }
  }
  for (std::size_t i = 1; i < n; ++i) {
    const double ds = path[i].s_m - path[i - 1].s_m;
    v[i] = std::min(v[i], std::sqrt(v[i - 1] * v[i - 1] + 2.0 * config_.acceleration_mps2 * ds));
  }
  for (std::size_t i = n - 1; i-- > 0;) {
    const double ds = path[i + 1].s_m - path[i].s_m;
    v[i] = std::min(v[i], std::sqrt(v[i + 1] * v[i + 1] + 2.0 * config_.acceleration_mps2 * ds));
  }
  // If the path starts across the current heading, turn in place first.
  const double first_heading = path.size() > 1 ? path[1].heading_rad : path[0].heading_rad;
  if (std::abs(wrap_to_pi(first_heading - samples_.back().yaw_rad)) > kTurnInPlace_rad)
    turn_to(first_heading);
  TimedSample current = samples_.back();
  const double s0 = current.s_m;
  for (std::size_t i = 1; i < n; ++i) {
    if (turn_before[i]) {  // `current` is samples_.back(): stopped at sample i − 1
      turn_to(step_heading[i]);
      current = samples_.back();
    }
    const double ds = path[i].s_m - path[i - 1].s_m;
    // A step between two stops (a hairpin over several steps) is crawled at kCrawl_mps.
    const double speed_sum = v[i - 1] + v[i] > 0.0 ? v[i - 1] + v[i] : 2.0 * kCrawl_mps;
    const double dt = ds > 0.0 ? 2.0 * ds / speed_sum : 0.0;
    current.time_s += dt;
    current.s_m = s0 + path[i].s_m;
    current.speed_mps = v[i];
    current.floor_point = on_ground(path[i].position, ground_height);
    // Yaw follows the tangent, rate limited (the speed limit above keeps it close).
    const double max_turn = config_.yaw_rate_max_radps * dt;
    current.yaw_rad +=
        std::clamp(wrap_to_pi(path[i].heading_rad - current.yaw_rad), -max_turn, max_turn);
    samples_.push_back(current);
  }
}

Eigen::Vector3d Trajectory::on_ground(const Eigen::Vector3d& nominal,
                                      const GroundHeightFunction& ground_height) const {
  if (!ground_height) return nominal;
  Eigen::Vector3d point = nominal;
  if (const auto z = ground_height(nominal)) {
    point.z() = *z;
  } else if (!samples_.empty()) {
    point.z() = samples_.back().floor_point.z();
  }
  return point;
}

Trajectory::TimedSample Trajectory::sample_at(double time_s) const {
  if (samples_.empty()) return {};
  if (time_s <= samples_.front().time_s) return samples_.front();
  if (time_s >= samples_.back().time_s) {
    TimedSample last = samples_.back();
    last.time_s = time_s;
    last.speed_mps = 0.0;
    return last;
  }
  const auto after =
      std::upper_bound(samples_.begin(), samples_.end(), time_s,
                       [](double t, const TimedSample& sample) { return t < sample.time_s; });
  const TimedSample& b = *after;
  const TimedSample& a = *(after - 1);
  const double w = b.time_s > a.time_s ? (time_s - a.time_s) / (b.time_s - a.time_s) : 0.0;
  TimedSample out;
  out.time_s = time_s;
  out.s_m = a.s_m + w * (b.s_m - a.s_m);
  out.speed_mps = a.speed_mps + w * (b.speed_mps - a.speed_mps);
  out.yaw_rad = a.yaw_rad + w * (b.yaw_rad - a.yaw_rad);
  out.floor_point = a.floor_point + w * (b.floor_point - a.floor_point);
  return out;
}

Eigen::Vector3d Trajectory::floor_point(double time_s) const {
  return sample_at(time_s).floor_point;
}
double Trajectory::speed(double time_s) const {
  return sample_at(time_s).speed_mps;
}
double Trajectory::yaw(double time_s) const {
  return wrap_to_pi(tracked_yaw(time_s));
}

Eigen::Isometry3d Trajectory::T_map_sensor(double time_s) const {
  const TimedSample sample = sample_at(time_s);
  Eigen::Vector3d position = sample.floor_point + Eigen::Vector3d(0, 0, config_.sensor_height_m);
  double yaw = tracked_yaw(time_s);
  double pitch = config_.mount_pitch_deg * M_PI / 180.0;
  double roll = config_.mount_roll_deg * M_PI / 180.0;
  if (config_.style == MotionStyle::Handheld) {
    // Gait phase from the distance walked, so a standing person does not bob: one stride (two
    // steps) is 2π. Bob once per step, sway and roll once per stride; slow hand wander on top.
    const double phase = M_PI * sample.s_m / config_.step_length_m;
    const double tilt = config_.hand_tilt_deg * M_PI / 180.0;
    const Eigen::Vector3d left(-std::sin(yaw), std::cos(yaw), 0.0);
    position.z() += config_.bob_m * std::cos(2.0 * phase);
    position += config_.sway_m * std::sin(phase) * left;
    auto wander = [&](int i) {
      return std::sin(2.0 * M_PI * wander_frequency_hz_[i] * time_s + wander_phase_rad_[i]);
    };
    roll += 0.5 * tilt * std::sin(phase) + 0.5 * tilt * wander(0) + 0.25 * tilt * wander(3);
    pitch += 0.4 * tilt * std::sin(2.0 * phase) + 0.6 * tilt * wander(1) + 0.3 * tilt * wander(4);
    yaw += 0.5 * tilt * wander(2) + 0.25 * tilt * wander(5);
  }
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = position;
  // R = Rz(yaw)·Ry(pitch)·Rx(roll) (ZYX, as localizer::make_pose).
  pose.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  return pose;
}

}  // namespace conicloc::sim
