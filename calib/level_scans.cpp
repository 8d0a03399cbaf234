#include "calib/level_scans.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace conicloc::calib {

LevelScanChoice choose_level_scans(std::span<const double> times_s,
                                   std::span<const double> floor_z_m, std::size_t first,
                                   std::size_t count, double max_climb_mps) {
  if (times_s.size() != floor_z_m.size()) {
    throw std::invalid_argument("choose_level_scans: " + std::to_string(times_s.size()) +
                                " times for " + std::to_string(floor_z_m.size()) +
                                " floor heights");
  }
  if (first == 0)
    throw std::invalid_argument("choose_level_scans: the first scan has none before it");
  // |Δz| ≤ rate·Δt between scans i and j (a NaN floor or time is not level).
  const auto level_between = [&](std::size_t i, std::size_t j) {
    return std::abs(floor_z_m[j] - floor_z_m[i]) <=
           max_climb_mps * std::abs(times_s[j] - times_s[i]);
  };
  std::vector<std::size_t> level;
  LevelScanChoice out;
  for (std::size_t i = first; i < floor_z_m.size(); ++i) {
    const bool after = i + 1 >= floor_z_m.size() || level_between(i, i + 1);
    if (level_between(i - 1, i) && after) {
      level.push_back(i);
    } else {
      ++out.climbing;
    }
  }
  const std::size_t taken = std::min(count, level.size());
  for (std::size_t k = 0; k < taken; ++k) out.chosen.push_back(level[k * level.size() / taken]);
  return out;
}

}  // namespace conicloc::calib
