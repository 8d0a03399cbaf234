#include "sim/vlp16_simulator.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>

namespace conicloc::sim {
namespace {

constexpr double kChannelSpacing_s = 2.304e-6;  // VLP-16 manual, firing timing
// Two echoes closer than this merge into one (the VLP-16 separates echoes ~ a metre apart at
// best; 0.3 m is used so mixed edge pixels show up in dual mode).
constexpr double kEchoSeparation_m = 0.3;

double quantise(double range_m, double step_m) {
  return step_m > 0.0 ? std::round(range_m / step_m) * step_m : range_m;
}

}  // namespace

SensorStats& SensorStats::operator+=(const SensorStats& other) {
  rays += other.rays;
  map_hits += other.map_hits;
  furniture_hits += other.furniture_hits;
  person_hits += other.person_hits;
  dropouts += other.dropouts;
  no_surface += other.no_surface;
  blind_zone += other.blind_zone;
  second_echoes += other.second_echoes;
  return *this;
}

Vlp16Simulator::Vlp16Simulator(const World& world, sensor::LaserCalibration calibration,
                               SensorConfig config, SensorEffects effects, std::mt19937_64& rng)
    : world_(world),
      nominal_(calibration),
      calibration_(std::move(calibration)),
      config_(config),
      effects_(effects) {
  const double bound_rad = effects_.elevation_error_deg * M_PI / 180.0;
  std::uniform_real_distribution<double> error(-1.0, 1.0);
  for (int k = 0; k < calibration_.ring_count(); ++k) {
    elevation_errors_rad_.push_back(bound_rad > 0.0 ? bound_rad * error(rng) : 0.0);
    calibration_.lasers[k].elevation_rad += elevation_errors_rad_.back();
  }
  // Drawn after the elevations, so a recording without offset errors keeps its elevations.
  std::normal_distribution<double> gaussian(0.0, 1.0);
  for (auto& laser : calibration_.lasers) {
    const double vertical = gaussian(rng), azimuth = gaussian(rng), range = gaussian(rng);
    laser.vertical_offset_m += effects_.offset_error_m * vertical;
    laser.azimuth_offset_rad += effects_.azimuth_error_deg * M_PI / 180.0 * azimuth;
    laser.range_offset_m += effects_.offset_error_m * range;
  }
  for (int k = 0; k < calibration_.ring_count(); ++k) {
    const auto& laser = calibration_.lasers[k];
    const double delta = laser.azimuth_offset_rad - angular_rate() * k * kChannelSpacing_s;
    directions_.push_back({std::cos(laser.elevation_rad), std::sin(laser.elevation_rad),
                           std::cos(delta), std::sin(delta)});
  }
  cos_half_divergence_ = std::cos(0.5 * config_.beam_divergence_rad);
  sin_half_divergence_ = std::sin(0.5 * config_.beam_divergence_rad);
}

double Vlp16Simulator::angular_rate() const {
  return config_.rpm / 60.0 * 2.0 * M_PI;
}

double Vlp16Simulator::azimuth_at(double time_s) const {
  const double theta = config_.start_azimuth_rad - angular_rate() * time_s;
  return theta - 2.0 * M_PI * std::floor(theta / (2.0 * M_PI));
}

Ray Vlp16Simulator::beam_ray(const Eigen::Isometry3d& T_map_sensor, int channel,
                             double cos_azimuth, double sin_azimuth) const {
  const auto& laser = calibration_.lasers[channel];
  const auto& dir = directions_[channel];
  // DESIGN.md: p(r) = (0, 0, o_k) + r·(cos φ cos θ, cos φ sin θ, sin φ), sensor frame.
  const Eigen::Vector3d direction_sensor(dir.cos_elevation * cos_azimuth,
                                         dir.cos_elevation * sin_azimuth, dir.sin_elevation);
  Ray ray;
  ray.origin = T_map_sensor * Eigen::Vector3d(0.0, 0.0, laser.vertical_offset_m);
  ray.direction = T_map_sensor.linear() * direction_sensor;
  return ray;
}

Vlp16Simulator::Echo Vlp16Simulator::echo_of(const std::optional<WorldHit>& hit) {
  Echo echo;
  if (!hit) return echo;
  echo.range_m = hit->range_m;
  // Calibrated reflectivity is range-compensated by the sensor; a Lambertian surface still
  // returns less at grazing incidence.
  echo.intensity = hit->material.reflectivity * (0.25 + 0.75 * hit->cos_incidence);
  echo.origin = hit->material.origin;
  return echo;
}

Vlp16Simulator::FanCast Vlp16Simulator::cast_fan(std::span<const Ray> rays, double time_s,
                                                 double max_cast_m,
                                                 const std::array<int, 16>& hints) const {
  // The map's surfaces first, for every ray: how far each reaches tells which people it may meet
  // (World::people_in_reach), out of all those walking the building.
  FanCast cast;
  std::array<double, 16> reach_m{};
  const std::size_t fan = rays.size();
  world_.nearest_surfaces(rays, 0.0, max_cast_m, std::span<const int>(hints.data(), fan),
                          std::span<std::optional<WorldHit>>(cast.surfaces.data(), fan));
  for (std::size_t k = 0; k < fan; ++k) {
    reach_m[k] = cast.surfaces[k] ? cast.surfaces[k]->range_m : max_cast_m;
  }
  cast.people = world_.people_in_reach(time_s, rays, std::span<const double>(reach_m.data(), fan));
  return cast;
}

io::FiringSequence Vlp16Simulator::fire(double time_s, double device_time_offset_s,
                                        const Eigen::Isometry3d& T_map_sensor, std::mt19937_64& rng,
                                        std::array<int, 16>& hints, SensorStats& stats) const {
  io::FiringSequence sequence;
  sequence.time_s = time_s + device_time_offset_s;
  sequence.azimuth_rad = azimuth_at(time_s);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  // Applies noise, quantisation and the range window: 0 means no return (too far), −1 none
  // either (too near: the blind zone).
  auto measure = [&](double range_m) {
    double measured = range_m;
    if (effects_.range_noise_m > 0.0) measured += effects_.range_noise_m * noise(rng);
    measured = quantise(measured, effects_.quantisation_m);
    if (measured <= effects_.min_range_m) return -1.0;
    return measured <= effects_.max_range_m ? measured : 0.0;
  };
  // Intensity jitter ±2 (uniform: a Gaussian per ray is the costliest part of the noise).
  auto to_intensity = [&](double value) {
    return static_cast<std::uint8_t>(
        std::clamp(std::lround(value + 4.0 * (unit(rng) - 0.5)), 1L, 100L));
  };
  const int channels = std::min(calibration_.ring_count(), 16);
  const double cos_sequence = std::cos(sequence.azimuth_rad);
  const double sin_sequence = std::sin(sequence.azimuth_rad);
  // From the sensor on, not from min_range_m: a surface in the blind zone stops the beam (the
  // return is then too near to be measured), it does not let the beam on to the wall behind.
  const double max_cast_m = effects_.max_range_m + 1.0;
  std::array<Ray, 16> rays;
  std::array<double, 16> cos_azimuth{}, sin_azimuth{};
  for (int k = 0; k < channels; ++k) {
    // θ_k = θ_seq + δ_k: cos θ_k = cos θ cos δ − sin θ sin δ, sin θ_k = sin θ cos δ + cos θ sin δ.
    const auto& dir = directions_[k];
    cos_azimuth[k] = cos_sequence * dir.cos_delta - sin_sequence * dir.sin_delta;
    sin_azimuth[k] = sin_sequence * dir.cos_delta + cos_sequence * dir.sin_delta;
    rays[k] = beam_ray(T_map_sensor, k, cos_azimuth[k], sin_azimuth[k]);
  }
  const auto fan = static_cast<std::size_t>(channels);
  const FanCast centre =
      cast_fan(std::span<const Ray>(rays.data(), fan), time_s, max_cast_m, hints);
  // Dual: the edge of the beam footprint (half the divergence behind the centre) may see a
  // different surface: a mixed pixel at an edge gives a second echo. The edges are cast as a fan
  // of their own, and meet the people their own reach allows.
  std::array<Ray, 16> edge_rays;
  FanCast edge;
  if (config_.dual_return) {
    for (int k = 0; k < channels; ++k) {
      edge_rays[k] =
          beam_ray(T_map_sensor, k,
                   cos_azimuth[k] * cos_half_divergence_ - sin_azimuth[k] * sin_half_divergence_,
                   sin_azimuth[k] * cos_half_divergence_ + cos_azimuth[k] * sin_half_divergence_);
    }
    edge = cast_fan(std::span<const Ray>(edge_rays.data(), fan), time_s, max_cast_m, hints);
  }
  for (int k = 0; k < channels; ++k) {
    ++stats.rays;
    const auto hit =
        world_.nearer_person(rays[k], centre.people, 0.0, max_cast_m, centre.surfaces[k]);
    // The next firing's hint: the polygon this laser hit (a person in front keeps the last one).
    if (hit && hit->polygon >= 0) hints[k] = hit->polygon;
    const Echo main = echo_of(hit);
    if (main.range_m <= 0.0 || main.range_m > effects_.max_range_m) {
      ++stats.no_surface;
      continue;
    }
    if (effects_.dropout_rate > 0.0 && unit(rng) < effects_.dropout_rate) {
      ++stats.dropouts;
      continue;
    }
    const double range_m = measure(main.range_m - calibration_.lasers[k].range_offset_m);
    if (range_m <= 0.0) {
      ++(range_m < 0.0 ? stats.blind_zone : stats.no_surface);
      continue;
    }
    switch (main.origin) {
      case SurfaceOrigin::Map:
        ++stats.map_hits;
        break;
      case SurfaceOrigin::Furniture:
        ++stats.furniture_hits;
        break;
      case SurfaceOrigin::Person:
        ++stats.person_hits;
        break;
    }
    sequence.range_m[k] = range_m;
    sequence.intensity[k] = to_intensity(main.intensity);
    if (!config_.dual_return) continue;
    const Echo edge_echo =
        echo_of(world_.nearer_person(edge_rays[k], edge.people, 0.0, max_cast_m, edge.surfaces[k]));
    const double edge_range_m =
        edge_echo.range_m > 0.0 ? measure(edge_echo.range_m - calibration_.lasers[k].range_offset_m)
                                : 0.0;
    if (edge_range_m <= 0.0 || std::abs(edge_range_m - range_m) < kEchoSeparation_m) continue;
    ++stats.second_echoes;
    // Encoder: range_m = last echo, second_range_m = strongest (second strongest when the
    // strongest is also the last). The beam centre is always the strongest echo.
    const std::uint8_t edge_intensity = to_intensity(0.5 * edge_echo.intensity);
    if (edge_range_m > range_m) {
      sequence.second_range_m[k] = range_m;
      sequence.second_intensity[k] = sequence.intensity[k];
      sequence.range_m[k] = edge_range_m;
      sequence.intensity[k] = edge_intensity;
    } else {
      sequence.second_range_m[k] = edge_range_m;
      sequence.second_intensity[k] = edge_intensity;
    }
  }
  return sequence;
}

}  // namespace conicloc::sim
