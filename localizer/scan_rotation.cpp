#include "localizer/scan_rotation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace conicloc::localizer {

namespace {

constexpr int kBins = 1440;  // 0.25° bins
constexpr double kBinRad = 2.0 * M_PI / kBins;
constexpr double kLevelRad = 0.14;  // rings within ±8° of level see what stands at sensor height

int wrap_bin(int bin) {
  bin %= kBins;
  return bin < 0 ? bin + kBins : bin;
}

// A ring sampled more coarsely than the bins (1200 rpm: 0.4°) leaves every other bin empty, and
// two scans would then overlap at some shifts and not at others. Gaps of up to 2° between returns
// on one surface (ranges within 10 %) are filled by linear interpolation.
void fill_gaps(std::vector<float>& bins) {
  constexpr int kMaxGap = 8;
  int last = -1;
  for (int b = 0; b < kBins; ++b) {
    if (bins[static_cast<std::size_t>(b)] <= 0.0f) continue;
    if (last >= 0 && b - last > 1 && b - last <= kMaxGap) {
      const float ra = bins[static_cast<std::size_t>(last)];
      const float rb = bins[static_cast<std::size_t>(b)];
      if (std::abs(ra - rb) <= 0.1f * std::max(ra, rb)) {
        for (int k = last + 1; k < b; ++k) {
          const float f = static_cast<float>(k - last) / static_cast<float>(b - last);
          bins[static_cast<std::size_t>(k)] = ra + f * (rb - ra);
        }
      }
    }
    last = b;
  }
}

}  // namespace

ScanRotation::Points ScanRotation::points_of(const sensor::Scan& scan) {
  Points points(scan.rings.size());
  for (std::size_t r = 0; r < scan.rings.size(); ++r) {
    const sensor::RingScan& ring = scan.rings[r];
    const double horizontal = std::cos(ring.elevation_rad);
    points[r].reserve(ring.returns.size());
    for (const sensor::Return& ret : ring.returns) {
      if (ret.status != sensor::ReturnStatus::Valid || !(ret.range_m > 0.0)) continue;
      const double d = ret.range_m * horizontal;
      points[r].emplace_back(d * std::cos(ret.azimuth_rad), d * std::sin(ret.azimuth_rad));
    }
  }
  return points;
}

ScanRotation::Profile ScanRotation::profile_of(const Points& points,
                                               const Eigen::Vector2d& offset) {
  Profile profile(points.size(), std::vector<float>(kBins, 0.0f));
  std::vector<int> counts(kBins);
  for (std::size_t r = 0; r < points.size(); ++r) {
    std::fill(counts.begin(), counts.end(), 0);
    std::vector<float>& bins = profile[r];
    for (const Eigen::Vector2d& point : points[r]) {
      const Eigen::Vector2d p = point - offset;
      const double azimuth = std::atan2(p.y(), p.x());
      const int bin = wrap_bin(static_cast<int>(std::floor(azimuth / kBinRad)));
      bins[static_cast<std::size_t>(bin)] += static_cast<float>(p.norm());
      ++counts[static_cast<std::size_t>(bin)];
    }
    for (int b = 0; b < kBins; ++b) {
      const int count = counts[static_cast<std::size_t>(b)];
      if (count > 1) bins[static_cast<std::size_t>(b)] /= static_cast<float>(count);
    }
    fill_gaps(bins);
  }
  return profile;
}

double ScanRotation::cost(const Profile& now, const Profile& before, int shift_bins, int stride,
                          std::size_t& overlap) const {
  double sum = 0.0;
  overlap = 0;
  const std::size_t rings = std::min(now.size(), before.size());
  for (std::size_t r = 0; r < rings; ++r) {
    const std::vector<float>& a = now[r];
    const std::vector<float>& b = before[r];
    for (int bin = 0; bin < kBins; bin += stride) {
      const float ra = a[static_cast<std::size_t>(bin)];
      const float rb = b[static_cast<std::size_t>(wrap_bin(bin + shift_bins))];
      if (ra <= 0.0f || rb <= 0.0f) continue;
      const double scale = std::max(1.0, 0.5 * static_cast<double>(ra + rb));
      sum += std::min(std::abs(static_cast<double>(ra - rb)) / scale, config_.clip);
      ++overlap;
    }
  }
  return overlap > 0 ? sum / static_cast<double>(overlap) : std::numeric_limits<double>::infinity();
}

std::optional<Eigen::Vector2d> ScanRotation::refine_translation(const Points& now_points,
                                                                const Points& before_points,
                                                                const Eigen::Vector2d& expected,
                                                                int shift_bins) const {
  const Profile now = profile_of(now_points, Eigen::Vector2d::Zero());
  const int steps = static_cast<int>(std::round(config_.translation_search_m / config_.translation_step_m));
  Eigen::Vector2d best = expected;
  for (int axis = 0; axis < 2; ++axis) {
    std::vector<double> costs;
    for (int k = -steps; k <= steps; ++k) {
      Eigen::Vector2d t = best;
      t(axis) += k * config_.translation_step_m;
      std::size_t overlap = 0;
      costs.push_back(cost(now, profile_of(before_points, t), shift_bins, 1, overlap));
    }
    const auto k = static_cast<int>(std::min_element(costs.begin(), costs.end()) - costs.begin());
    // A minimum at the edge of the search, or without a dip, pins nothing.
    if (k < 3 || k + 3 >= static_cast<int>(costs.size())) return std::nullopt;
    const double away = 0.5 * (costs[static_cast<std::size_t>(k - 3)] + costs[static_cast<std::size_t>(k + 3)]);
    if (!(away > costs[static_cast<std::size_t>(k)] * (1.0 + config_.min_translation_dip)))
      return std::nullopt;
    double offset = 0.0;
    const double c0 = costs[static_cast<std::size_t>(k - 1)], c1 = costs[static_cast<std::size_t>(k)],
                 c2 = costs[static_cast<std::size_t>(k + 1)];
    if (c0 - 2.0 * c1 + c2 > 0.0) offset = std::clamp(0.5 * (c0 - c2) / (c0 - 2.0 * c1 + c2), -0.5, 0.5);
    best(axis) += (k - steps + offset) * config_.translation_step_m;
  }
  return best;
}

ScanRotation::FineTurn ScanRotation::fine_turn(const Profile& now, const Profile& before,
                                               int centre_shift) const {
  // Every bin, 0.25° steps within ±1° of `centre_shift`, then a parabola through the costs at
  // the minimum and its neighbours: the sub-bin shift.
  FineTurn fine;
  double costs[9];
  int best = 4;
  for (int k = 0; k < 9; ++k) {
    std::size_t overlap = 0;
    costs[k] = cost(now, before, centre_shift - 4 + k, 1, overlap);
    if (costs[k] < fine.cost) fine.cost = costs[k], best = k, fine.overlap = overlap;
  }
  double offset = 0.0;
  if (best > 0 && best < 8 && std::isfinite(costs[best - 1]) && std::isfinite(costs[best + 1])) {
    const double curvature = costs[best - 1] - 2.0 * costs[best] + costs[best + 1];
    if (curvature > 0.0) offset = 0.5 * (costs[best - 1] - costs[best + 1]) / curvature;
  }
  fine.shift_bins = centre_shift - 4 + best;
  fine.turn_rad = (fine.shift_bins + std::clamp(offset, -0.5, 0.5)) * kBinRad;
  return fine;
}

ScanRotation::Motion ScanRotation::update(const sensor::Scan& scan,
                                          const Eigen::Vector2d& translation_m) {
  Points points = points_of(scan);
  std::vector<double> elevations;
  for (const auto& ring : scan.rings) elevations.push_back(ring.elevation_rad);
  if (previous_.empty()) {
    previous_ = std::move(points);
    elevations_rad_ = std::move(elevations);
    return {};
  }
  const Points before_points = std::move(previous_);
  const std::vector<double> before_elevations = std::move(elevations_rad_);
  previous_ = points;
  elevations_rad_ = elevations;

  const Profile now = profile_of(points, Eigen::Vector2d::Zero());
  // The previous scan as seen from the position it was expected to move to (before the turn).
  const Profile before = profile_of(before_points, translation_m);
  std::size_t possible = 0;
  for (const auto& ring : now) {
    for (const float range : ring) possible += range > 0.0f ? 1 : 0;
  }
  // Coarse: 1° steps on every 4th bin; keep the best and the best at least 5° from it.
  const int max_shift = static_cast<int>(std::ceil(config_.max_rotation_rad / kBinRad));
  std::vector<double> coarse;
  std::vector<int> shifts;
  for (int shift = -max_shift; shift <= max_shift; shift += 4) {
    std::size_t overlap = 0;
    coarse.push_back(cost(now, before, shift, 4, overlap));
    shifts.push_back(shift);
  }
  const auto best = static_cast<std::size_t>(
      std::min_element(coarse.begin(), coarse.end()) - coarse.begin());
  double rival = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < coarse.size(); ++k) {
    if (std::abs(shifts[k] - shifts[best]) >= 20) rival = std::min(rival, coarse[k]);
  }
  FineTurn fine = fine_turn(now, before, shifts[best]);
  if (!std::isfinite(fine.cost) ||
      static_cast<double>(fine.overlap) < config_.min_overlap * static_cast<double>(possible) ||
      !(rival > fine.cost * (1.0 + config_.min_distinctness)))
    return {};

  // The near-level rings, every 3rd return, for the translation.
  Points level_now(points.size()), level_before(before_points.size());
  for (std::size_t r = 0; r < points.size() && r < before_points.size(); ++r) {
    if (r >= before_elevations.size() || std::abs(before_elevations[r]) > kLevelRad ||
        std::abs(elevations[r]) > kLevelRad)
      continue;
    for (std::size_t i = 0; i < points[r].size(); i += 3) level_now[r].push_back(points[r][i]);
    for (std::size_t i = 0; i < before_points[r].size(); i += 3)
      level_before[r].push_back(before_points[r][i]);
  }
  Motion motion;
  motion.translation_m = refine_translation(level_now, level_before, translation_m, fine.shift_bins);
  // The turn again, from the previous scan moved by the translation found.
  if (motion.translation_m)
    fine = fine_turn(now, profile_of(before_points, *motion.translation_m), fine.shift_bins);
  motion.turn_rad = fine.turn_rad;
  return motion;
}

ScanRotation::Turn ScanRotation::end_to_end(double turn_rad,
                                            std::optional<double> previous_turn_rad,
                                            double sigma_rad) {
  if (!previous_turn_rad) return {turn_rad, sigma_rad + 0.5 * std::abs(turn_rad)};
  const double change = turn_rad - *previous_turn_rad;
  return {turn_rad + 0.5 * change, sigma_rad + 0.5 * std::abs(change)};
}

}  // namespace conicloc::localizer
