#include "localizer/filter/scan_turn.hpp"

#include <algorithm>
#include <cmath>

#include "parallel/parallel_for.hpp"

namespace conicloc::localizer {

namespace {

// The sub-step offset of the minimum of a parabola through three equally spaced costs.
double parabola_offset(double before, double at, double after) {
  const double curvature = before - 2.0 * at + after;
  if (!(curvature > 0.0) || !std::isfinite(curvature)) return 0.0;
  return std::clamp(0.5 * (before - after) / curvature, -0.5, 0.5);
}

}  // namespace

ScanTurn::FineTurn ScanTurn::fine_turn(const RangeProfile& now, const RangeProfile& before,
                                       int centre_shift) const {
  // Every bin, 0.25° steps within ±1° of `centre_shift`, then the parabola's sub-bin offset.
  FineTurn fine;
  double costs[9];
  std::size_t overlaps[9];
  parallel_for(9, threads_, [&](std::size_t begin, std::size_t end, int) {
    for (std::size_t k = begin; k < end; ++k) {
      costs[k] = profile_cost(now, before, centre_shift - 4 + static_cast<int>(k), 1, config_.clip,
                              overlaps[k]);
    }
  });
  int best = 4;
  for (int k = 0; k < 9; ++k) {
    if (costs[k] < fine.cost) fine.cost = costs[k], best = k, fine.overlap = overlaps[k];
  }
  const double offset =
      best > 0 && best < 8 ? parabola_offset(costs[best - 1], costs[best], costs[best + 1]) : 0.0;
  fine.shift_bins = centre_shift - 4 + best;
  fine.turn_rad = (fine.shift_bins + offset) * kProfileBinRad;
  return fine;
}

std::optional<double> ScanTurn::update(const sensor::Scan& scan,
                                       const Eigen::Vector2d& expected_translation_m) {
  const RingPoints points = ring_points(scan, threads_);
  const RingPoints before_points = std::move(previous_);
  previous_ = points;
  if (before_points.empty()) return std::nullopt;

  // The turn, from the previous scan seen from where the sensor was expected to go.
  const RangeProfile now = range_profile(points, Eigen::Vector2d::Zero(), threads_);
  const RangeProfile before = range_profile(before_points, expected_translation_m, threads_);
  const int max_shift = static_cast<int>(std::ceil(config_.max_rotation_rad / kProfileBinRad));
  std::vector<int> shifts;
  for (int shift = -max_shift; shift <= max_shift; shift += 4) shifts.push_back(shift);  // 1°
  std::vector<double> coarse(shifts.size());
  parallel_for(shifts.size(), threads_, [&](std::size_t begin, std::size_t end, int) {
    for (std::size_t k = begin; k < end; ++k) {
      std::size_t overlap = 0;
      coarse[k] = profile_cost(now, before, shifts[k], 4, config_.clip, overlap);
    }
  });
  const auto best =
      static_cast<std::size_t>(std::min_element(coarse.begin(), coarse.end()) - coarse.begin());
  double rival = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < coarse.size(); ++k) {
    if (std::abs(shifts[k] - shifts[best]) >= 20) rival = std::min(rival, coarse[k]);
  }
  FineTurn fine = fine_turn(now, before, shifts[best]);
  if (!std::isfinite(fine.cost) ||
      static_cast<double>(fine.overlap) <
          config_.min_overlap * static_cast<double>(filled_bins(now)) ||
      !(rival > fine.cost * (1.0 + config_.min_distinctness)))
    return std::nullopt;

  return fine.turn_rad;
}

ScanTurn::Turn ScanTurn::end_to_end(double turn_rad, std::optional<double> previous_turn_rad,
                                    double sigma_rad) {
  if (!previous_turn_rad) return {turn_rad, sigma_rad + 0.5 * std::abs(turn_rad)};
  const double change = turn_rad - *previous_turn_rad;
  return {turn_rad + 0.5 * change, sigma_rad + 0.5 * std::abs(change)};
}

}  // namespace conicloc::localizer
