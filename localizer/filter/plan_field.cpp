#include "localizer/filter/plan_field.hpp"

#include <algorithm>
#include <cmath>

#include "maps/segment_distance.hpp"

namespace conicloc::localizer {

PlanField::PlanField(const std::vector<maps::SectionSegment>& walls,
                     const Eigen::AlignedBox2d& extent, double resolution_m, double sigma_m,
                     int levels)
    : origin_(extent.isEmpty() ? Eigen::Vector2d::Zero() : extent.min()),
      resolution_m_(resolution_m) {
  if (!extent.isEmpty()) {
    width_ = static_cast<int>(std::ceil(extent.sizes().x() / resolution_m)) + 1;
    height_ = static_cast<int>(std::ceil(extent.sizes().y() / resolution_m)) + 1;
  }
  levels_.assign(1, std::vector<std::uint8_t>(static_cast<std::size_t>(width_) *
                                              static_cast<std::size_t>(height_)));
  if (width_ > 0 && height_ > 0)
    for (const maps::SectionSegment& wall : walls) paint(wall, sigma_m);
  build_pyramid(std::max(levels, 1));
}

void PlanField::paint(const maps::SectionSegment& wall, double sigma_m) {
  // Every cell within 3σ of the segment: its bounding box grown by 3σ.
  const Eigen::Vector2d a = wall.a.head<2>(), b = wall.b.head<2>();
  const double reach = 3.0 * sigma_m;
  const auto index = [&](double v, double o) {
    return static_cast<int>(std::floor((v - o) / resolution_m_));
  };
  const int i0 = std::max(index(std::min(a.x(), b.x()) - reach, origin_.x()), 0);
  const int i1 = std::min(index(std::max(a.x(), b.x()) + reach, origin_.x()), width_ - 1);
  const int j0 = std::max(index(std::min(a.y(), b.y()) - reach, origin_.y()), 0);
  const int j1 = std::min(index(std::max(a.y(), b.y()) + reach, origin_.y()), height_ - 1);
  std::vector<std::uint8_t>& field = levels_[0];
  const double inverse_two_variance = 1.0 / (2.0 * sigma_m * sigma_m);
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) {
      const Eigen::Vector2d centre = origin_ + resolution_m_ * Eigen::Vector2d(i + 0.5, j + 0.5);
      const double d2 = maps::squared_distance_to_segment(centre, a, b);
      if (d2 > reach * reach) continue;
      const auto value =
          static_cast<std::uint8_t>(std::lround(255.0 * std::exp(-d2 * inverse_two_variance)));
      std::uint8_t& cell = field[static_cast<std::size_t>(j) * static_cast<std::size_t>(width_) +
                                 static_cast<std::size_t>(i)];
      cell = std::max(cell, value);
    }
  }
}

void PlanField::build_pyramid(int levels) {
  // L_k(i, j) = max of L_{k−1} at (i, j), (i + h, j), (i, j + h), (i + h, j + h), h = 2^(k−1):
  // two windows of 2^(k−1) side by side in each direction make one of 2^k.
  for (int k = 1; k < levels; ++k) {
    const int half = 1 << (k - 1);
    std::vector<std::uint8_t> next(levels_.back().size());
    for (int j = 0; j < height_; ++j) {
      for (int i = 0; i < width_; ++i) {
        next[static_cast<std::size_t>(j) * static_cast<std::size_t>(width_) +
             static_cast<std::size_t>(i)] =
            std::max({at(k - 1, i, j), at(k - 1, i + half, j), at(k - 1, i, j + half),
                      at(k - 1, i + half, j + half)});
      }
    }
    levels_.push_back(std::move(next));
  }
}

std::size_t PlanField::memory_bytes() const {
  std::size_t bytes = 0;
  for (const auto& level : levels_) bytes += level.size();
  return bytes;
}

}  // namespace conicloc::localizer
