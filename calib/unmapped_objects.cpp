#include "calib/unmapped_objects.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "localizer/filter/median.hpp"

namespace conicloc::calib {

std::vector<std::vector<std::size_t>> scan_lines(std::span<const Return> returns) {
  std::map<std::pair<int, int>, std::vector<std::size_t>> by_line;
  for (std::size_t i = 0; i < returns.size(); ++i)
    by_line[{returns[i].scan, returns[i].laser}].push_back(i);
  std::vector<std::vector<std::size_t>> lines;
  lines.reserve(by_line.size());
  for (auto& [key, line] : by_line) {
    std::stable_sort(line.begin(), line.end(), [&](std::size_t a, std::size_t b) {
      return returns[a].azimuth_rad < returns[b].azimuth_rad;
    });
    lines.push_back(std::move(line));
  }
  return lines;
}

double robust_sigma(std::span<const double> residual_m, std::span<const int> plane) {
  std::vector<double> magnitude;
  for (std::size_t i = 0; i < residual_m.size(); ++i)
    if (plane[i] >= 0) magnitude.push_back(std::abs(residual_m[i]));
  return 1.4826 * localizer::median_of(magnitude);
}

std::size_t leave_out_unmapped_objects(const std::vector<std::vector<std::size_t>>& lines,
                                       std::span<const double> residual_m, std::vector<int>& plane,
                                       double sigma_m, const UnmappedObjectConfig& config) {
  const std::vector<int> surface = plane;  // the medians see every return of the round
  const double median_scale = std::sqrt(M_PI / 2.0) * sigma_m;
  std::vector<double> window;
  std::size_t left_out = 0;
  for (const auto& line : lines) {
    const std::ptrdiff_t size = static_cast<std::ptrdiff_t>(line.size());
    for (std::ptrdiff_t k = 0; k < size; ++k) {
      const int polygon = surface[line[k]];
      if (polygon < 0) continue;
      window.clear();
      for (std::ptrdiff_t j = std::max<std::ptrdiff_t>(0, k - config.half_window);
           j <= std::min(size - 1, k + config.half_window); ++j) {
        if (surface[line[j]] == polygon) window.push_back(residual_m[line[j]]);
      }
      if (static_cast<int>(window.size()) < config.min_neighbours) continue;
      const double limit =
          config.median_sigmas * median_scale / std::sqrt(static_cast<double>(window.size()));
      if (std::abs(localizer::median_of(window)) > limit) {
        plane[line[k]] = -1;
        ++left_out;
      }
    }
  }
  return left_out;
}

std::size_t leave_out_unmapped_objects(const std::vector<std::vector<std::size_t>>& lines,
                                       std::span<const double> residual_m, std::vector<int>& plane,
                                       const UnmappedObjectConfig& config) {
  const double sigma_m = std::max(robust_sigma(residual_m, plane), config.min_sigma_m);
  return leave_out_unmapped_objects(lines, residual_m, plane, sigma_m, config);
}

}  // namespace conicloc::calib
