#include "localizer/filter/resampling.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_set>

namespace conicloc::localizer {

std::vector<std::size_t> low_variance_resample(std::span<const double> normalised_log_weights,
                                               std::size_t count, double u0) {
  std::vector<std::size_t> selected;
  if (normalised_log_weights.empty() || count == 0) return selected;
  selected.reserve(count);
  const double step = 1.0 / static_cast<double>(count);
  std::size_t i = 0;
  double cumulative = std::exp(normalised_log_weights[0]);
  const std::size_t last = normalised_log_weights.size() - 1;
  for (std::size_t m = 0; m < count; ++m) {
    const double pointer = (u0 + static_cast<double>(m)) * step;
    // `>=` skips leading zero weights at pointer 0; `i < last` guards against the cumulative sum
    // ending a rounding error below one.
    while (pointer >= cumulative && i < last) cumulative += std::exp(normalised_log_weights[++i]);
    selected.push_back(i);
  }
  return selected;
}

std::size_t kld_sample_count(std::size_t occupied_bins, double epsilon, double z_quantile) {
  if (occupied_bins <= 1) return 1;
  const double k_minus_1 = static_cast<double>(occupied_bins - 1);
  const double a = 2.0 / (9.0 * k_minus_1);
  const double cube = std::pow(1.0 - a + std::sqrt(a) * z_quantile, 3.0);
  return static_cast<std::size_t>(std::ceil(k_minus_1 / (2.0 * epsilon) * cube));
}

std::uint64_t kld_bin_key(const Particle& particle, const KldBins& bins) {
  // Pack the bin coordinates into one key: 12 bits for x and y (2 km at 0.5 m), 8 for the rest;
  // a rare wrap-around only merges two bins.
  const auto bin = [](double value, double size, std::uint64_t mask) {
    return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(value / size))) & mask;
  };
  const PoseState& s = particle.state;
  return bin(s.x, bins.xy_m, 0xFFF) | bin(s.y, bins.xy_m, 0xFFF) << 12 |
         bin(s.z, bins.z_m, 0xFF) << 24 | bin(s.yaw + M_PI, bins.yaw_rad, 0xFF) << 32 |
         bin(particle.velocity_x, bins.velocity_m_s, 0xFF) << 40 |
         bin(particle.velocity_y, bins.velocity_m_s, 0xFF) << 48;
}

std::size_t count_occupied_bins(const ParticleSet& particles, std::span<const std::size_t> indices,
                                const KldBins& bins) {
  std::unordered_set<std::uint64_t> occupied;
  occupied.reserve(indices.size());
  for (const std::size_t index : indices) occupied.insert(kld_bin_key(particles[index], bins));
  return occupied.size();
}

}  // namespace conicloc::localizer
