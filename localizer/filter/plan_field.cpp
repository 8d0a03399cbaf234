#include "localizer/filter/plan_field.hpp"

#include <algorithm>
#include <cmath>

#include "maps/segment_distance.hpp"

namespace conicloc::localizer {

PlanField::PlanField(const std::vector<maps::SectionSegment>& walls,
                     const Eigen::AlignedBox2d& extent, double resolution_m, double sigma_m,
                     int levels, int padding_cells)
    : resolution_m_(resolution_m) {
  padding_cells = std::max(padding_cells, 0);
  if (!extent.isEmpty())
    origin_ = extent.min() - Eigen::Vector2d::Constant(padding_cells * resolution_m);
  int inner_width = 0, inner_height = 0;
  if (!extent.isEmpty()) {
    inner_width = static_cast<int>(std::ceil(extent.sizes().x() / resolution_m)) + 1;
    inner_height = static_cast<int>(std::ceil(extent.sizes().y() / resolution_m)) + 1;
    width_ = inner_width + 2 * padding_cells;
    height_ = inner_height + 2 * padding_cells;
  }
  levels_.assign(1, std::vector<std::uint8_t>(static_cast<std::size_t>(width_) *
                                              static_cast<std::size_t>(height_)));
  if (inner_width > 0 && inner_height > 0) {
    const Eigen::AlignedBox2i inner(
        Eigen::Vector2i::Constant(padding_cells),
        Eigen::Vector2i(padding_cells + inner_width - 1, padding_cells + inner_height - 1));
    for (const maps::SectionSegment& wall : walls) paint(wall, sigma_m, inner);
  }
  build_pyramid(std::max(levels, 1));
}

void PlanField::paint(const maps::SectionSegment& wall, double sigma_m,
                      const Eigen::AlignedBox2i& inner) {
  // Every cell within 3σ of the segment: its bounding box grown by 3σ.
  const Eigen::Vector2d a = wall.a.head<2>(), b = wall.b.head<2>();
  const double reach = 3.0 * sigma_m;
  const auto index = [&](double v, double o) {
    return static_cast<int>(std::floor((v - o) / resolution_m_));
  };
  const int i0 = std::max(index(std::min(a.x(), b.x()) - reach, origin_.x()), inner.min().x());
  const int i1 = std::min(index(std::max(a.x(), b.x()) + reach, origin_.x()), inner.max().x());
  const int j0 = std::max(index(std::min(a.y(), b.y()) - reach, origin_.y()), inner.min().y());
  const int j1 = std::min(index(std::max(a.y(), b.y()) + reach, origin_.y()), inner.max().y());
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
  // two windows of 2^(k−1) side by side in each direction make one of 2^k. Taken as the maximum
  // along rows, then along columns of that; cells past the grid's end count 0.
  const auto w = static_cast<std::size_t>(width_), h = static_cast<std::size_t>(height_);
  std::vector<std::uint8_t> rows(w * h);
  for (int k = 1; k < levels; ++k) {
    const auto half = static_cast<std::size_t>(1) << (k - 1);
    const std::vector<std::uint8_t>& previous = levels_.back();
    for (std::size_t j = 0; j < h; ++j) {
      const std::uint8_t* in = previous.data() + j * w;
      std::uint8_t* out = rows.data() + j * w;
      for (std::size_t i = 0; i < w; ++i)
        out[i] = i + half < w ? std::max(in[i], in[i + half]) : in[i];
    }
    std::vector<std::uint8_t> next(w * h);
    for (std::size_t j = 0; j < h; ++j) {
      const std::uint8_t* in = rows.data() + j * w;
      std::uint8_t* out = next.data() + j * w;
      if (j + half < h) {
        const std::uint8_t* below = in + half * w;
        for (std::size_t i = 0; i < w; ++i) out[i] = std::max(in[i], below[i]);
      } else {
        std::copy(in, in + w, out);
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
