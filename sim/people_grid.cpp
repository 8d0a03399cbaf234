#include "sim/people_grid.hpp"

#include <algorithm>
#include <cmath>

namespace conicloc::sim {
namespace {

// Cells about as wide as a room: a firing's reach up to its walls spans a few of them. About
// 2^20 cells at most for a building of any size, unless it is thousands of times longer than
// wide.
constexpr double kCell_m = 5.0;
constexpr double kMaxCells = 1 << 20;

}  // namespace

PeopleGrid::PeopleGrid(const std::vector<Eigen::AlignedBox2d>& walks) {
  if (walks.empty()) return;
  Eigen::AlignedBox2d extent;
  for (const auto& walk : walks) extent.extend(walk);
  origin_ = extent.min();
  const Eigen::Vector2d size = extent.sizes();
  cell_m_ = std::max(kCell_m, std::sqrt(size.x() * size.y() / kMaxCells));
  columns_ = static_cast<int>(size.x() / cell_m_) + 1;
  rows_ = static_cast<int>(size.y() / cell_m_) + 1;
  // Counting sort of (cell, person) pairs into one array, cell by cell.
  std::vector<std::uint32_t> counts(static_cast<std::size_t>(columns_) * rows_ + 1, 0);
  walk_cells_.reserve(walks.size());
  for (const auto& walk : walks) {
    const CellRange r = cells_of(walk);
    walk_cells_.push_back(r);
    for (int y = r.y0; y <= r.y1; ++y) {
      for (int x = r.x0; x <= r.x1; ++x) ++counts[static_cast<std::size_t>(y) * columns_ + x + 1];
    }
  }
  for (std::size_t c = 1; c < counts.size(); ++c) counts[c] += counts[c - 1];
  first_ = counts;
  people_.resize(first_.back());
  for (std::size_t i = 0; i < walks.size(); ++i) {
    const CellRange& r = walk_cells_[i];
    for (int y = r.y0; y <= r.y1; ++y) {
      for (int x = r.x0; x <= r.x1; ++x) {
        people_[counts[static_cast<std::size_t>(y) * columns_ + x]++] =
            static_cast<std::uint32_t>(i);
      }
    }
  }
}

PeopleGrid::CellRange PeopleGrid::cells_of(const Eigen::AlignedBox2d& box) const {
  const auto cell = [&](double value, double lo, int count) {
    const double c = std::floor((value - lo) / cell_m_);
    return static_cast<int>(std::clamp(c, 0.0, static_cast<double>(count - 1)));
  };
  return {cell(box.min().x(), origin_.x(), columns_), cell(box.min().y(), origin_.y(), rows_),
          cell(box.max().x(), origin_.x(), columns_), cell(box.max().y(), origin_.y(), rows_)};
}

bool PeopleGrid::query_cells(const Eigen::Vector2d& point, double distance,
                             CellRange& cells) const {
  if (walk_cells_.empty()) return false;
  const Eigen::AlignedBox2d square(point.array() - distance, point.array() + distance);
  // A square wholly off the grid meets no walk (the grid spans them all); nor does a NaN one.
  if (!square.intersects(
          Eigen::AlignedBox2d(origin_, origin_ + cell_m_ * Eigen::Vector2d(columns_, rows_)))) {
    return false;
  }
  cells = cells_of(square);
  return true;
}

}  // namespace conicloc::sim
