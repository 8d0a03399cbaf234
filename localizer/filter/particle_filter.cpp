#include "localizer/filter/particle_filter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>

#include "localizer/filter/adaptive_tempering.hpp"
#include "localizer/filter/log_weights.hpp"
#include "parallel/parallel_for.hpp"

namespace conicloc::localizer {

namespace {

std::vector<double> log_weights_of(const ParticleSet& particles) {
  std::vector<double> weights(particles.size());
  for (std::size_t i = 0; i < particles.size(); ++i) weights[i] = particles[i].log_weight;
  return weights;
}

}  // namespace

void ParticleFilter::set_uniform_weights() {
  const double uniform =
      -std::log(static_cast<double>(std::max<std::size_t>(particles_.size(), 1)));
  for (Particle& p : particles_) p.log_weight = uniform;
}

double ParticleFilter::position_spread_m() const {
  double mass = 0.0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), sum_squares = Eigen::Vector3d::Zero();
  for (const Particle& p : particles_) {
    const double w = std::exp(p.log_weight);
    const Eigen::Vector3d position(p.state.x, p.state.y, p.state.z);
    mass += w;
    sum += w * position;
    sum_squares += w * position.cwiseProduct(position);
  }
  if (!(mass > 0.0)) return 0.0;
  const Eigen::Vector3d mean = sum / mass;
  // Var = E[x²] − E[x]²: fine for building-sized coordinates near the map origin.
  return std::sqrt(std::max((sum_squares / mass - mean.cwiseProduct(mean)).sum(), 0.0));
}

bool ParticleFilter::searching() const {
  if (position_spread_m() <= config_.adaptive_min_spread_m) return false;
  // The mode's centre: the weighted median in x and in y, which lies inside any mode holding
  // more than half the weight (after a resampling every weight is equal but a kept runner-up's,
  // and a "heaviest particle" would be an arbitrary one); its heading is that of the particle
  // nearest to it.
  const std::size_t n = particles_.size();
  std::vector<double> weights(n);
  for (std::size_t i = 0; i < n; ++i) weights[i] = std::exp(particles_[i].log_weight);
  const auto weighted_median = [&](auto coordinate) {
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return coordinate(particles_[a]) < coordinate(particles_[b]);
    });
    const double half = 0.5 * std::accumulate(weights.begin(), weights.end(), 0.0);
    double cumulative = 0.0;
    for (const std::size_t i : order) {
      cumulative += weights[i];
      if (cumulative >= half) return coordinate(particles_[i]);
    }
    return coordinate(particles_[order.back()]);
  };
  const double centre_x = weighted_median([](const Particle& p) { return p.state.x; });
  const double centre_y = weighted_median([](const Particle& p) { return p.state.y; });
  const auto nearest = std::min_element(
      particles_.begin(), particles_.end(), [&](const Particle& a, const Particle& b) {
        return std::hypot(a.state.x - centre_x, a.state.y - centre_y) <
               std::hypot(b.state.x - centre_x, b.state.y - centre_y);
      });
  PoseState centre = nearest->state;
  centre.x = centre_x;
  centre.y = centre_y;
  double mass = 0.0, mode_mass = 0.0, sum_x = 0.0, sum_y = 0.0, sum_xx = 0.0, sum_yy = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Particle& p = particles_[i];
    const double w = weights[i];
    mass += w;
    if (!in_mode(p.state, centre, config_.mode)) continue;
    const double dx = p.state.x - centre_x, dy = p.state.y - centre_y;
    mode_mass += w;
    sum_x += w * dx, sum_y += w * dy, sum_xx += w * dx * dx, sum_yy += w * dy * dy;
  }
  if (!(mode_mass > 0.0) || mode_mass < config_.settled_mode_weight * mass) return true;
  const double mean_x = sum_x / mode_mass, mean_y = sum_y / mode_mass;
  const double mode_spread = std::sqrt(
      std::max(sum_xx / mode_mass - mean_x * mean_x + sum_yy / mode_mass - mean_y * mean_y, 0.0));
  return mode_spread > config_.adaptive_min_spread_m;
}

void ParticleFilter::initialise_at(const PoseState& mean, const Vector6& sigma, std::size_t count,
                                   std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  particles_.assign(std::max<std::size_t>(count, 1), Particle{});
  for (Particle& p : particles_) {
    PoseState& s = p.state;
    s.x = mean.x + sigma(0) * normal(rng);
    s.y = mean.y + sigma(1) * normal(rng);
    s.z = mean.z + sigma(2) * normal(rng);
    s.roll = mean.roll + sigma(3) * normal(rng);
    s.pitch = mean.pitch + sigma(4) * normal(rng);
    s.yaw = angle_difference(mean.yaw + sigma(5) * normal(rng), 0.0);
    motion_.update_cell(p);
    if (p.cell < 0) p.floor_z = mean.z - motion_.config().height_above_floor_m;
    motion_.draw_initial_velocity(p, rng);
  }
  set_uniform_weights();
}

Particle ParticleFilter::global_particle(std::mt19937_64& rng,
                                         const HeadingProposal& headings) const {
  const FreeSpace::Sample sample = free_space_.sample(rng);
  Particle p;
  p.state.x = sample.point_on_floor.x();
  p.state.y = sample.point_on_floor.y();
  p.state.yaw = headings.draw(rng);
  p.cell = sample.cell;
  p.floor_z = sample.point_on_floor.z();
  p.state.z = p.floor_z + motion_.config().height_above_floor_m;
  p.state.roll = motion_.config().roll_rad;
  p.state.pitch = motion_.config().pitch_rad;
  motion_.draw_initial_velocity(p, rng);
  return p;
}

Particle ParticleFilter::local_particle(const RestartMix& mix, std::mt19937_64& rng) const {
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int attempt = 0; attempt < 20; ++attempt) {
    Particle p;
    p.state = mix.centre;
    p.state.x += mix.local_sigma_xy_m * normal(rng);
    p.state.y += mix.local_sigma_xy_m * normal(rng);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    p.state.yaw =
        unit(rng) < mix.local_heading_fraction
            ? mix.headings.draw(rng)
            : angle_difference(mix.centre.yaw + mix.local_sigma_yaw_rad * normal(rng), 0.0);
    // The storey of the last good pose: its floor is the hint for the cell.
    p.floor_z = mix.centre.z - motion_.config().height_above_floor_m;
    p.cell = -1;
    motion_.update_cell(p);
    if (p.cell < 0) continue;
    motion_.place_on_floor(p);
    motion_.draw_initial_velocity(p, rng);
    return p;
  }
  return global_particle(rng, mix.headings);
}

void ParticleFilter::initialise_global(std::size_t count, std::mt19937_64& rng) {
  particles_.clear();
  if (free_space_.empty()) return;
  particles_.reserve(count);
  const std::size_t per_position = std::max<std::size_t>(config_.headings_per_position, 1);
  for (std::size_t i = 0; i < std::max<std::size_t>(count, 1); ++i) {
    if (i % per_position == 0) {
      particles_.push_back(global_particle(rng));
    } else {
      Particle p = particles_[i - i % per_position];  // the group's position
      motion_.draw_initial_velocity(p, rng);
      particles_.push_back(p);
    }
  }
  draw_headings(HeadingProposal(), per_position, rng);
  set_uniform_weights();
}

void ParticleFilter::draw_headings(const HeadingProposal& headings, std::size_t per_position,
                                   std::mt19937_64& rng) {
  per_position = std::max<std::size_t>(per_position, 1);
  for (std::size_t begin = 0; begin < particles_.size(); begin += per_position) {
    const std::size_t end = std::min(begin + per_position, particles_.size());
    const std::vector<double> yaws = headings.draw_spread(end - begin, rng);
    for (std::size_t i = begin; i < end; ++i) particles_[i].state.yaw = yaws[i - begin];
  }
}

Particle ParticleFilter::particle_about(const PlanCandidate& candidate, double sigma_xy_m,
                                        double sigma_yaw_rad,
                                        std::normal_distribution<double>& normal,
                                        std::mt19937_64& rng) const {
  Particle p;
  // The candidate's storey: its floor is the hint for the cell. A draw off every navigable
  // floor (into a wall's thickness, out of the building) is drawn again, and after 20 misses
  // stays on the candidate; a draw into the next room keeps that room's floor.
  p.state.z = candidate.floor_z + motion_.config().height_above_floor_m;
  for (int attempt = 0; attempt < 20 && p.cell < 0; ++attempt) {
    p.state.x = candidate.x + sigma_xy_m * normal(rng);
    p.state.y = candidate.y + sigma_xy_m * normal(rng);
    motion_.update_cell(p);
  }
  if (p.cell < 0) {
    p.state.x = candidate.x;
    p.state.y = candidate.y;
  }
  motion_.place_on_floor(p);
  p.state.yaw = angle_difference(candidate.yaw + sigma_yaw_rad * normal(rng), 0.0);
  motion_.draw_initial_velocity(p, rng);
  return p;
}

void ParticleFilter::draw_about(const std::vector<PlanCandidate>& candidates, std::size_t first,
                                std::size_t count, double sigma_xy_m, double sigma_yaw_rad,
                                std::mt19937_64& rng) {
  if (candidates.empty()) return;
  std::normal_distribution<double> normal(0.0, 1.0);
  const std::size_t end = std::min(first + count, particles_.size());
  for (std::size_t i = first; i < end; ++i)
    particles_[i] = particle_about(candidates[(i - first) % candidates.size()], sigma_xy_m,
                                   sigma_yaw_rad, normal, rng);
  set_uniform_weights();
}

void ParticleFilter::add_hypotheses(const std::vector<PlanCandidate>& candidates,
                                    std::size_t particles_each, double sigma_xy_m,
                                    double sigma_yaw_rad, std::mt19937_64& rng) {
  const std::size_t n = particles_.size();
  if (n == 0 || candidates.empty() || particles_each == 0) return;
  // Added, not swapped for the lightest particles: those may be a kept runner-up's, the truth
  // in a minority. The next resampling brings the count back to its target.
  const double mean_weight = -std::log(static_cast<double>(n));
  std::normal_distribution<double> normal(0.0, 1.0);
  for (const PlanCandidate& candidate : candidates) {
    for (std::size_t k = 0; k < particles_each; ++k) {
      Particle p = particle_about(candidate, sigma_xy_m, sigma_yaw_rad, normal, rng);
      p.log_weight = mean_weight;
      particles_.push_back(p);
    }
  }
  std::vector<double> log_weights(particles_.size());
  for (std::size_t i = 0; i < particles_.size(); ++i) log_weights[i] = particles_[i].log_weight;
  normalise_log_weights(log_weights);
  for (std::size_t i = 0; i < particles_.size(); ++i) particles_[i].log_weight = log_weights[i];
}

WeightSummary ParticleFilter::weight(
    const ObservationModel& model,
    std::vector<std::unique_ptr<ObservationModel::Scratch>>& scratches, double climb_fraction,
    const RefinementScale& scale) {
  WeightSummary summary;
  const std::size_t n = particles_.size();
  if (n == 0) return summary;
  std::vector<ObservationScore> scores(n);
  const int threads = static_cast<int>(std::max<std::size_t>(scratches.size(), 1));
  parallel_for(n, threads, [&](std::size_t begin, std::size_t end, int worker) {
    ObservationModel::Scratch* scratch =
        scratches.empty() ? nullptr : scratches[static_cast<std::size_t>(worker)].get();
    for (std::size_t i = begin; i < end; ++i) {
      Pose3 T_map_view = particles_[i].state.to_pose();
      T_map_view.translation().z() += climb_fraction * particles_[i].floor_rise_m;
      scores[i] = model.score(T_map_view, scratch);
    }
  });
  if (config_.refinement.hypotheses > 0 && scale.step_m > 0.0 && searching()) {
    refine_leaders(model, scratches, climb_fraction, scale, scores);
  }
  // Serial from here: the order of the sums does not depend on the thread count.
  std::size_t best = 0;
  for (std::size_t i = 0; i < n; ++i) {
    // `>` is false for NaN, so a NaN score never becomes the best.
    if (scores[i].log_likelihood > scores[best].log_likelihood ||
        std::isnan(scores[best].log_likelihood)) {
      best = i;
    }
  }
  // What the scan is worth, seen from the pose that explains it best (correlated_terms.hpp).
  const double terms = static_cast<double>(std::max<std::size_t>(model.term_count(), 1));
  Pose3 T_map_best = particles_[best].state.to_pose();
  T_map_best.translation().z() += climb_fraction * particles_[best].floor_rise_m;
  // Serial: the first worker's scratch is free.
  summary.effective_terms =
      model.effective_terms(T_map_best, scratches.empty() ? nullptr : scratches.front().get());
  double independent = summary.effective_terms;
  if (config_.reference_terms > 0.0) independent = std::min(independent, config_.reference_terms);
  const double max_tempering = config_.tempering * std::min(1.0, independent / terms);
  std::vector<double> log_weights = log_weights_of(particles_);
  std::vector<double> log_likelihoods(n);
  for (std::size_t i = 0; i < n; ++i) log_likelihoods[i] = scores[i].log_likelihood;
  const double tempering = adaptive_tempering_exponent(
      log_weights, log_likelihoods, max_tempering,
      searching() ? config_.adaptive_ess_fraction : config_.tracking_ess_fraction);
  summary.tempering = tempering;
  summary.max_tempering = max_tempering;
  for (std::size_t i = 0; i < n; ++i) {
    log_weights[i] += tempering * scores[i].log_likelihood;
    if (std::isnan(log_weights[i])) log_weights[i] = -std::numeric_limits<double>::infinity();
  }
  summary.best = best;
  summary.best_log_likelihood = scores[best].log_likelihood;
  summary.best_inlier_fraction = scores[best].inlier_fraction;
  summary.all_minus_infinity = !std::isfinite(normalise_log_weights(log_weights));
  for (std::size_t i = 0; i < n; ++i) particles_[i].log_weight = log_weights[i];
  summary.ess = effective_sample_size(log_weights);
  return summary;
}

void ParticleFilter::refine_leaders(
    const ObservationModel& model,
    std::vector<std::unique_ptr<ObservationModel::Scratch>>& scratches, double climb_fraction,
    const RefinementScale& scale, std::vector<ObservationScore>& scores) {
  const std::vector<std::size_t> leaders =
      leading_hypotheses(particles_, scores, config_.kld_bins, config_.refinement.hypotheses);
  const int threads = static_cast<int>(std::max<std::size_t>(scratches.size(), 1));
  parallel_for(leaders.size(), threads, [&](std::size_t begin, std::size_t end, int worker) {
    ObservationModel::Scratch* scratch =
        scratches.empty() ? nullptr : scratches[static_cast<std::size_t>(worker)].get();
    const auto evaluate = [&](std::size_t index,
                              Particle& candidate) -> std::optional<ObservationScore> {
      motion_.follow_floor(candidate);
      // A hypothesis on the navigable floor stays on it.
      if (candidate.cell < 0 && particles_[index].cell >= 0) return std::nullopt;
      Pose3 T_map_view = candidate.state.to_pose();
      T_map_view.translation().z() += climb_fraction * candidate.floor_rise_m;
      return model.score(T_map_view, scratch);
    };
    for (std::size_t k = begin; k < end; ++k) {
      const std::size_t index = leaders[k];
      refine_hypothesis(particles_[index], scores[index], index, scale, config_.refinement,
                        evaluate);
    }
  });
}

bool ParticleFilter::resample_if_needed(std::mt19937_64& rng, bool keep_runner_ups) {
  const std::size_t n = particles_.size();
  if (n == 0) return false;
  const std::vector<double> log_weights = log_weights_of(particles_);
  if (effective_sample_size(log_weights) >=
      config_.resample_ess_fraction * static_cast<double>(n)) {
    return false;
  }
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  // Pass 1 measures how many histogram bins the posterior occupies; pass 2 draws the KLD count.
  std::vector<std::size_t> selected = low_variance_resample(log_weights, n, unit(rng));
  const std::size_t bins = count_occupied_bins(particles_, selected, config_.kld_bins);
  // While the cloud is spread (searching: global start, recovery) it keeps the full count even
  // when one hypothesis leads: the KLD bound measures the leader's size, but a minority mode —
  // often the true one, found later as the sensor moves out of an ambiguous room — must keep
  // enough particles to win back the weight.
  const std::size_t kld_min = searching() ? config_.max_particles : config_.min_particles;
  const std::size_t target = std::clamp(
      kld_sample_count(bins, config_.kld_epsilon, config_.kld_z_quantile),
      std::max<std::size_t>(kld_min, 1), std::max(config_.max_particles, config_.min_particles));
  // The runner-up modes that proportional resampling would leave with too few particles: each
  // becomes a group of its own (Particle::hypothesis 1, 2, …); group 0 is the rest of the cloud.
  const RunnerUpConfig& runner_ups = config_.runner_ups;
  std::vector<int> group(n, 0);
  int kept_groups = 0;
  if (keep_runner_ups && runner_ups.max_runner_ups > 0 && runner_ups.min_particles > 0) {
    const Modes modes =
        find_modes(particles_, config_.mode, 1 + runner_ups.max_runner_ups, runner_ups.min_weight);
    std::vector<int> group_of_mode(modes.weight.size(), 0);
    for (std::size_t k = 1; k < modes.weight.size(); ++k) {
      if (modes.weight[k] * static_cast<double>(target) <
          static_cast<double>(runner_ups.min_particles)) {
        group_of_mode[k] = ++kept_groups;
      }
    }
    for (std::size_t i = 0; i < n; ++i)
      if (modes.mode_of[i] >= 0)
        group[i] = group_of_mode[static_cast<std::size_t>(modes.mode_of[i])];
  }
  ParticleSet resampled;
  if (kept_groups == 0) {
    if (target != n) selected = low_variance_resample(log_weights, target, unit(rng));
    resampled.reserve(selected.size());
    for (const std::size_t index : selected) resampled.push_back(particles_[index]);
    particles_ = std::move(resampled);
    set_uniform_weights();
    for (Particle& p : particles_) p.hypothesis = 0;
    return true;
  }
  // Draws `count` copies from group `g`, in proportion to their weights, each weighted
  // mass / count: the group keeps its share of the probability.
  const auto draw_group = [&](int g, std::size_t count) {
    std::vector<double> members = log_weights;
    for (std::size_t i = 0; i < n; ++i)
      if (group[i] != g) members[i] = -std::numeric_limits<double>::infinity();
    const double log_mass = normalise_log_weights(members);
    if (!std::isfinite(log_mass)) return;
    const double log_weight = log_mass - std::log(static_cast<double>(count));
    for (const std::size_t index : low_variance_resample(members, count, unit(rng))) {
      Particle copy = particles_[index];
      copy.log_weight = log_weight;
      copy.hypothesis = g;
      resampled.push_back(copy);
    }
  };
  resampled.reserve(target + static_cast<std::size_t>(kept_groups) * runner_ups.min_particles);
  draw_group(0, target);
  for (int g = 1; g <= kept_groups; ++g) draw_group(g, runner_ups.min_particles);
  particles_ = std::move(resampled);
  return true;
}

void ParticleFilter::roughen(std::mt19937_64& rng) {
  const std::size_t n = particles_.size();
  if (n < 2) return;
  // Extents per hypothesis (one, the whole cloud, unless runner-ups were kept apart): a kept
  // runner-up 20 m away must not widen the leader's jitter to decimetres. Runner-ups heavy
  // enough to keep their particles by weight, and strays, stay in the leader's group.
  struct Extent {
    double min_x = std::numeric_limits<double>::infinity(), max_x = -min_x;
    double min_y = min_x, max_y = -min_x;
    // Yaw spread about the group's first particle, so a group straddling ±π is not 2π wide.
    double min_yaw = min_x, max_yaw = -min_x;
    std::optional<double> yaw0;
  };
  int groups = 1;
  for (const Particle& p : particles_) groups = std::max(groups, p.hypothesis + 1);
  std::vector<Extent> extents(static_cast<std::size_t>(groups));
  for (const Particle& p : particles_) {
    Extent& e = extents[static_cast<std::size_t>(std::max(p.hypothesis, 0))];
    e.min_x = std::min(e.min_x, p.state.x), e.max_x = std::max(e.max_x, p.state.x);
    e.min_y = std::min(e.min_y, p.state.y), e.max_y = std::max(e.max_y, p.state.y);
    if (!e.yaw0) e.yaw0 = p.state.yaw;
    const double dyaw = angle_difference(p.state.yaw, *e.yaw0);
    e.min_yaw = std::min(e.min_yaw, dyaw), e.max_yaw = std::max(e.max_yaw, dyaw);
  }
  const double scale = config_.roughening_k * std::pow(static_cast<double>(n), -1.0 / 3.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (Particle& p : particles_) {
    const Extent& e = extents[static_cast<std::size_t>(std::max(p.hypothesis, 0))];
    const double sigma_x = std::max(scale * (e.max_x - e.min_x), config_.roughening_min_xy_m);
    const double sigma_y = std::max(scale * (e.max_y - e.min_y), config_.roughening_min_xy_m);
    const double sigma_yaw =
        std::max(scale * (e.max_yaw - e.min_yaw), config_.roughening_min_yaw_rad);
    p.state.x += sigma_x * normal(rng);
    p.state.y += sigma_y * normal(rng);
    p.state.yaw = angle_difference(p.state.yaw + sigma_yaw * normal(rng), 0.0);
    motion_.follow_floor(p);
  }
}

void ParticleFilter::inject_global(double fraction, std::mt19937_64& rng) {
  const std::size_t n = particles_.size();
  if (free_space_.empty() || n == 0) return;
  const std::size_t count = std::clamp<std::size_t>(
      static_cast<std::size_t>(std::ceil(std::clamp(fraction, 0.0, 1.0) * static_cast<double>(n))),
      1, n);
  for (std::size_t j = 0; j < count; ++j) particles_[j * n / count] = global_particle(rng);
  set_uniform_weights();
}

std::size_t ParticleFilter::restart(std::size_t count, const RestartMix& mix,
                                    std::mt19937_64& rng) {
  if (free_space_.empty() || particles_.empty()) return particles_.size();
  count = std::max<std::size_t>(count, 1);
  const auto share = [count](double fraction) {
    return static_cast<std::size_t>(
        std::floor(std::clamp(fraction, 0.0, 1.0) * static_cast<double>(count)));
  };
  const std::size_t kept = share(mix.keep_fraction);
  const std::size_t local = std::min(share(mix.local_fraction), count - kept);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  ParticleSet restarted;
  restarted.reserve(count);
  if (kept > 0) {
    const std::vector<double> log_weights = log_weights_of(particles_);
    for (const std::size_t index : low_variance_resample(log_weights, kept, unit(rng)))
      restarted.push_back(particles_[index]);
  }
  while (restarted.size() < kept + local) restarted.push_back(local_particle(mix, rng));
  const std::size_t first_global = restarted.size();
  while (restarted.size() < count) restarted.push_back(global_particle(rng, mix.headings));
  particles_ = std::move(restarted);
  set_uniform_weights();
  return first_global;
}

Eigen::AlignedBox3d ParticleFilter::position_bounds() const {
  Eigen::AlignedBox3d box;
  for (const Particle& p : particles_) box.extend(Eigen::Vector3d(p.state.x, p.state.y, p.state.z));
  return box;
}

}  // namespace conicloc::localizer
