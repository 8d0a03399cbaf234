#include "localizer/free_space.hpp"

#include <algorithm>
#include <cmath>

namespace conicloc::localizer {

namespace {

maps::Ring2 rectangle_of(const Eigen::AlignedBox3d& bounds) {
  const Eigen::Vector3d lo = bounds.min();
  const Eigen::Vector3d hi = bounds.max();
  return {{lo.x(), lo.y()}, {hi.x(), lo.y()}, {hi.x(), hi.y()}, {lo.x(), hi.y()}};
}

}  // namespace

FreeSpace::FreeSpace(const maps::PlaneMap& map) : map_(map) {
  area_of_cell_.assign(map.cells.size(), -1);
  Eigen::AlignedBox2d all;
  for (std::size_t c = 0; c < map.cells.size(); ++c) {
    const maps::Cell& cell = map.cells[c];
    if (!cell.navigable) continue;
    CellArea area;
    area.cell = static_cast<int>(c);
    area.footprint = cell.footprint.size() >= 3 ? cell.footprint
                     : cell.bounds.isEmpty()    ? maps::Ring2{}
                                                : rectangle_of(cell.bounds);
    if (area.footprint.size() < 3) continue;
    const double area_m2 = std::abs(maps::signed_area(area.footprint));
    if (!(area_m2 > 0.0)) continue;
    for (const auto& v : area.footprint) area.box.extend(v);
    area.floor_z = cell.floor_z;
    area_of_cell_[c] = static_cast<int>(areas_.size());
    all.extend(area.box);
    areas_.push_back(std::move(area));
    total_area_m2_ += area_m2;
    cumulative_area_m2_.push_back(total_area_m2_);
  }
  if (areas_.empty()) return;
  // About 4 footprints per grid square on average, squares at least 0.5 m.
  const Eigen::Vector2d extent = all.sizes();
  grid_cell_m_ = std::max(0.5, std::sqrt(extent.x() * extent.y() / (4.0 * areas_.size() + 1.0)));
  grid_min_ = all.min();
  grid_nx_ = static_cast<int>(std::floor(extent.x() / grid_cell_m_)) + 1;
  grid_ny_ = static_cast<int>(std::floor(extent.y() / grid_cell_m_)) + 1;
  grid_.assign(static_cast<std::size_t>(grid_nx_) * grid_ny_, {});
  for (std::size_t a = 0; a < areas_.size(); ++a) {
    const Eigen::Vector2d lo = (areas_[a].box.min() - grid_min_) / grid_cell_m_;
    const Eigen::Vector2d hi = (areas_[a].box.max() - grid_min_) / grid_cell_m_;
    for (int ix = std::max(0, static_cast<int>(lo.x()));
         ix <= std::min(grid_nx_ - 1, static_cast<int>(hi.x())); ++ix) {
      for (int iy = std::max(0, static_cast<int>(lo.y()));
           iy <= std::min(grid_ny_ - 1, static_cast<int>(hi.y())); ++iy) {
        grid_[static_cast<std::size_t>(iy) * grid_nx_ + ix].push_back(static_cast<int>(a));
      }
    }
  }
}

bool FreeSpace::holds(const CellArea& area, double x, double y) const {
  const Eigen::Vector2d p(x, y);
  return area.box.contains(p) && maps::ring_contains(area.footprint, p);
}

int FreeSpace::cell_at(double x, double y, double z_m, double floor_tolerance_m) const {
  if (areas_.empty() || !std::isfinite(x) || !std::isfinite(y)) return -1;
  const double fx = (x - grid_min_.x()) / grid_cell_m_;
  const double fy = (y - grid_min_.y()) / grid_cell_m_;
  if (fx < 0.0 || fy < 0.0 || fx >= grid_nx_ || fy >= grid_ny_) return -1;
  const auto& candidates =
      grid_[static_cast<std::size_t>(fy) * grid_nx_ + static_cast<std::size_t>(fx)];
  int below = -1;  // highest floor not above the sensor
  int above = -1;  // lowest floor above it
  for (const int a : candidates) {
    const CellArea& area = areas_[a];
    if (!holds(area, x, y)) continue;
    if (area.floor_z <= z_m + floor_tolerance_m) {
      if (below < 0 || area.floor_z > areas_[below].floor_z) below = a;
    } else if (above < 0 || area.floor_z < areas_[above].floor_z) {
      above = a;
    }
  }
  const int chosen = below >= 0 ? below : above;
  return chosen >= 0 ? areas_[chosen].cell : -1;
}

int FreeSpace::cell_at(double x, double y, double z_m, int hint_cell) const {
  if (hint_cell >= 0 && hint_cell < static_cast<int>(area_of_cell_.size())) {
    const int a = area_of_cell_[hint_cell];
    // The hint is only safe on single-storey spots; a stair cell may overlap the one below.
    if (a >= 0 && holds(areas_[a], x, y) && map_.storeys.size() <= 1) return hint_cell;
  }
  return cell_at(x, y, z_m);
}

FreeSpace::Sample FreeSpace::sample(std::mt19937_64& rng) const {
  if (areas_.empty()) return {};
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double pick = unit(rng) * total_area_m2_;
  const auto it = std::upper_bound(cumulative_area_m2_.begin(), cumulative_area_m2_.end(), pick);
  const std::size_t a = std::min<std::size_t>(it - cumulative_area_m2_.begin(), areas_.size() - 1);
  const CellArea& area = areas_[a];
  // Rejection sampling in the footprint's box; footprints fill a good part of their box, and
  // after many misses (a sliver) the vertex mean is used.
  for (int attempt = 0; attempt < 1000; ++attempt) {
    const double x = area.box.min().x() + unit(rng) * area.box.sizes().x();
    const double y = area.box.min().y() + unit(rng) * area.box.sizes().y();
    if (maps::ring_contains(area.footprint, {x, y})) return {{x, y, area.floor_z}, area.cell};
  }
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& v : area.footprint) mean += v;
  mean /= static_cast<double>(area.footprint.size());
  return {{mean.x(), mean.y(), area.floor_z}, area.cell};
}

double FreeSpace::floor_z(int cell) const {
  if (cell < 0 || cell >= static_cast<int>(map_.cells.size())) return 0.0;
  return map_.cells[cell].floor_z;
}

}  // namespace conicloc::localizer
