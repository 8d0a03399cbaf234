#include "localizer/filter/range_profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "parallel/parallel_for.hpp"

namespace conicloc::localizer {

namespace {

int wrap_bin(int bin) {
  bin %= kProfileBins;
  return bin < 0 ? bin + kProfileBins : bin;
}

void fill_gaps(std::vector<float>& bins) {
  constexpr int kMaxGap = 8;
  int last = -1;
  for (int b = 0; b < kProfileBins; ++b) {
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

RingPoints ring_points(const sensor::Scan& scan, int threads) {
  RingPoints points(scan.rings.size());
  parallel_for(scan.rings.size(), threads, [&](std::size_t begin, std::size_t end, int) {
    for (std::size_t r = begin; r < end; ++r) {
      const sensor::RingScan& ring = scan.rings[r];
      const double horizontal = std::cos(ring.elevation_rad);
      points[r].reserve(ring.returns.size());
      for (const sensor::Return& ret : ring.returns) {
        if (ret.status != sensor::ReturnStatus::Valid || !(ret.range_m > 0.0)) continue;
        const double d = ret.range_m * horizontal;
        points[r].emplace_back(d * std::cos(ret.azimuth_rad), d * std::sin(ret.azimuth_rad));
      }
    }
  });
  return points;
}

RangeProfile range_profile(const RingPoints& points, const Eigen::Vector2d& origin, int threads) {
  RangeProfile profile(points.size(), std::vector<float>(kProfileBins, 0.0f));
  parallel_for(points.size(), threads, [&](std::size_t begin, std::size_t end, int) {
    std::vector<int> counts(kProfileBins);
    for (std::size_t r = begin; r < end; ++r) {
      std::fill(counts.begin(), counts.end(), 0);
      std::vector<float>& bins = profile[r];
      for (const Eigen::Vector2d& point : points[r]) {
        const Eigen::Vector2d p = point - origin;
        const int bin =
            wrap_bin(static_cast<int>(std::floor(std::atan2(p.y(), p.x()) / kProfileBinRad)));
        bins[static_cast<std::size_t>(bin)] += static_cast<float>(p.norm());
        ++counts[static_cast<std::size_t>(bin)];
      }
      for (int b = 0; b < kProfileBins; ++b) {
        const int count = counts[static_cast<std::size_t>(b)];
        if (count > 1) bins[static_cast<std::size_t>(b)] /= static_cast<float>(count);
      }
      fill_gaps(bins);
    }
  });
  return profile;
}

double profile_cost(const RangeProfile& a, const RangeProfile& b, int shift_bins, int stride,
                    double clip, std::size_t& overlap) {
  double sum = 0.0;
  overlap = 0;
  const std::size_t rings = std::min(a.size(), b.size());
  for (std::size_t r = 0; r < rings; ++r) {
    for (int bin = 0; bin < kProfileBins; bin += stride) {
      const float ra = a[r][static_cast<std::size_t>(bin)];
      const float rb = b[r][static_cast<std::size_t>(wrap_bin(bin + shift_bins))];
      if (ra <= 0.0f || rb <= 0.0f) continue;
      const double scale = std::max(1.0, 0.5 * static_cast<double>(ra + rb));
      sum += std::min(std::abs(static_cast<double>(ra - rb)) / scale, clip);
      ++overlap;
    }
  }
  return overlap > 0 ? sum / static_cast<double>(overlap) : std::numeric_limits<double>::infinity();
}

std::size_t filled_bins(const RangeProfile& profile) {
  std::size_t count = 0;
  for (const auto& ring : profile) {
    for (const float range : ring) count += range > 0.0f ? 1 : 0;
  }
  return count;
}

}  // namespace conicloc::localizer
