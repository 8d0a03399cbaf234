#include "localizer/filter/free_space.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "maps/segment_distance.hpp"
#include "maps/walkable_ground.hpp"

namespace conicloc::localizer {

namespace {

// A floor up to this far above the sensor's current floor is still "its" floor (stair steps,
// floor noise); see cell_at().
constexpr double kFloorTolerance_m = 0.5;

// Points on the shared edge of two patches (a landing meeting the flight) are inside neither by
// the even-odd rule; within this distance of an outline they count as on it.
constexpr double kSeamTolerance_m = 1e-6;

bool on_outline(const maps::Ring2& ring, const Eigen::Vector2d& p) {
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    if (maps::squared_distance_to_segment(p, ring[j], ring[i]) <=
        kSeamTolerance_m * kSeamTolerance_m) {
      return true;
    }
  }
  return false;
}

maps::Ring2 rectangle_of(const Eigen::AlignedBox3d& bounds) {
  const Eigen::Vector3d lo = bounds.min();
  const Eigen::Vector3d hi = bounds.max();
  return {{lo.x(), lo.y()}, {hi.x(), lo.y()}, {hi.x(), hi.y()}, {lo.x(), hi.y()}};
}

}  // namespace

bool FreeSpace::FloorPatch::holds(double x, double y) const {
  const Eigen::Vector2d p(x, y);
  if (!box.contains(p) || !maps::ring_contains(outer_xy, p)) return false;
  for (const auto& hole : holes_xy) {
    if (maps::ring_contains(hole, p)) return false;
  }
  return true;
}

void FreeSpace::add_floor_patches(const maps::PlaneMap& map, int cell, CellArea& area) {
  for (const int index : map.cells[cell].polygons) {
    if (!maps::is_walkable_ground(map, index, cell)) continue;
    const maps::PlanarPolygon& polygon = map.polygons[index];
    const Eigen::Vector3d& n = polygon.plane.normal;
    FloorPatch patch;
    // n·p + d = 0 solved for z: z = −(n_x x + n_y y + d) / n_z.
    patch.slope_x = -n.x() / n.z();
    patch.slope_y = -n.y() / n.z();
    patch.z0 = -polygon.plane.offset / n.z();
    patch.outer_xy = maps::plan_view(polygon.outer);
    for (const auto& hole : polygon.holes) patch.holes_xy.push_back(maps::plan_view(hole));
    for (const auto& v : patch.outer_xy) patch.box.extend(v);
    patch.min_z = polygon.bounds.min().z();
    patch.max_z = polygon.bounds.max().z();
    area.floors.push_back(std::move(patch));
  }
}

double FreeSpace::floor_height(const CellArea& area, double x, double y, double z_hint_m) const {
  double below = -std::numeric_limits<double>::infinity();  // highest floor not above the hint
  double above = std::numeric_limits<double>::infinity();   // lowest floor above it
  for (const FloorPatch& patch : area.floors) {
    if (!patch.holds(x, y)) continue;
    const double z = patch.height_at(x, y);
    if (z <= z_hint_m + kFloorTolerance_m) {
      below = std::max(below, z);
    } else {
      above = std::min(above, z);
    }
  }
  if (std::isfinite(below)) return below;
  if (std::isfinite(above)) return above;
  // Off every patch (a seam between landing and flight, a hole, a footprint wider than the
  // floors): the nearest patch's plane, kept within its height range.
  double nearest_m2 = std::numeric_limits<double>::infinity();
  double z = area.floor_z;
  for (const FloorPatch& patch : area.floors) {
    const double d2 = patch.box.squaredExteriorDistance(Eigen::Vector2d(x, y));
    if (d2 < nearest_m2) {
      nearest_m2 = d2;
      z = std::clamp(patch.height_at(x, y), patch.min_z, patch.max_z);
    }
  }
  return z;
}

double FreeSpace::floor_z_at(int cell, double x, double y, double z_hint_m) const {
  if (cell < 0 || cell >= static_cast<int>(area_of_cell_.size())) return floor_z(cell);
  const int a = area_of_cell_[cell];
  return a >= 0 ? floor_height(areas_[a], x, y, z_hint_m) : floor_z(cell);
}

FreeSpace::FreeSpace(const maps::PlaneMap& map) : map_(map) {
  area_of_cell_.assign(map.cells.size(), -1);
  Eigen::AlignedBox2d all;
  for (std::size_t c = 0; c < map.cells.size(); ++c) {
    const maps::Cell& cell = map.cells[c];
    if (!cell.navigable) continue;
    CellArea area;
    area.cell = static_cast<int>(c);
    area.floor_z = cell.floor_z;
    add_floor_patches(map, static_cast<int>(c), area);
    if (area.floors.empty()) {
      // No walkable surface in the model: the footprint (else the bounds) at the cell's floor
      // (its thresholds' height, maps/floorless_cells.hpp, else its lowest vertex).
      FloorPatch flat;
      flat.outer_xy = cell.footprint.size() >= 3 ? cell.footprint
                      : cell.bounds.isEmpty()    ? maps::Ring2{}
                                                 : rectangle_of(cell.bounds);
      if (flat.outer_xy.size() < 3) continue;
      for (const auto& v : flat.outer_xy) flat.box.extend(v);
      flat.z0 = flat.min_z = flat.max_z = cell.floor_z;
      area.floors.push_back(std::move(flat));
    }
    area.lowest_floor_z = std::numeric_limits<double>::infinity();
    area.highest_floor_z = -std::numeric_limits<double>::infinity();
    for (const FloorPatch& patch : area.floors) {
      area.lowest_floor_z = std::min(area.lowest_floor_z, patch.min_z);
      area.highest_floor_z = std::max(area.highest_floor_z, patch.max_z);
    }
    const int a = static_cast<int>(areas_.size());
    for (int f = 0; f < static_cast<int>(area.floors.size()); ++f) {
      const FloorPatch& patch = area.floors[f];
      double area_m2 = std::abs(maps::signed_area(patch.outer_xy));
      for (const auto& hole : patch.holes_xy) area_m2 -= std::abs(maps::signed_area(hole));
      if (!(area_m2 > 0.0)) continue;
      area.box.extend(patch.box);
      total_area_m2_ += area_m2;
      cumulative_area_m2_.push_back(total_area_m2_);
      sample_patches_.emplace_back(a, f);
    }
    if (area.box.isEmpty()) continue;
    area_of_cell_[c] = a;
    all.extend(area.box);
    areas_.push_back(std::move(area));
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
  // Highest floors first (cell_at() stops at the first area that cannot reach the floor found).
  for (std::vector<int>& square : grid_) {
    std::stable_sort(square.begin(), square.end(), [this](int a, int b) {
      return areas_[a].highest_floor_z > areas_[b].highest_floor_z;
    });
  }
}

bool FreeSpace::holds(const CellArea& area, double x, double y) const {
  const Eigen::Vector2d p(x, y);
  Eigen::AlignedBox2d grown = area.box;
  grown.min().array() -= kSeamTolerance_m;
  grown.max().array() += kSeamTolerance_m;
  if (!grown.contains(p)) return false;
  for (const FloorPatch& patch : area.floors) {
    if (patch.holds(x, y)) return true;
  }
  // On a seam between two patches, or on the cell's outline.
  for (const FloorPatch& patch : area.floors) {
    if (on_outline(patch.outer_xy, p)) return true;
  }
  return false;
}

int FreeSpace::cell_at(double x, double y, double z_m, double floor_tolerance_m) const {
  if (areas_.empty() || !std::isfinite(x) || !std::isfinite(y)) return -1;
  const double fx = (x - grid_min_.x()) / grid_cell_m_;
  const double fy = (y - grid_min_.y()) / grid_cell_m_;
  if (fx < 0.0 || fy < 0.0 || fx >= grid_nx_ || fy >= grid_ny_) return -1;
  const auto& candidates =
      grid_[static_cast<std::size_t>(fy) * grid_nx_ + static_cast<std::size_t>(fx)];
  int below = -1;  // highest floor not above the sensor (the first area of the map on a tie)
  double below_floor = 0.0;
  // A floor lies within its area's heights (kHeightSlack_m for rounding). The areas come highest
  // floor first: those whose floors all lie above the sensor are looked at only when no floor
  // lies below it, and once one does, an area whose floors all lie under it ends the search. In
  // a stack of storeys, a particle tests the areas of its own storey, not every storey's.
  constexpr double kHeightSlack_m = 1e-6;
  for (const int a : candidates) {
    const CellArea& area = areas_[a];
    if (below >= 0 && area.highest_floor_z + kHeightSlack_m < below_floor) break;
    // Negated so that a NaN height finds no floor below it, as before.
    if (!(area.lowest_floor_z - kHeightSlack_m <= z_m + floor_tolerance_m)) continue;
    if (!holds(area, x, y)) continue;
    const double floor = floor_height(area, x, y, z_m);
    if (!(floor <= z_m + floor_tolerance_m)) continue;
    if (below < 0 || floor > below_floor || (floor == below_floor && a < below)) {
      below = a;
      below_floor = floor;
    }
  }
  if (below >= 0) return areas_[below].cell;
  int above = -1;  // lowest floor above the sensor
  double above_floor = 0.0;
  for (const int a : candidates) {
    const CellArea& area = areas_[a];
    if (!holds(area, x, y)) continue;
    const double floor = floor_height(area, x, y, z_m);
    if (above < 0 || floor < above_floor || (floor == above_floor && a < above)) {
      above = a;
      above_floor = floor;
    }
  }
  return above >= 0 ? areas_[above].cell : -1;
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
  const std::size_t k =
      std::min<std::size_t>(it - cumulative_area_m2_.begin(), sample_patches_.size() - 1);
  const CellArea& area = areas_[sample_patches_[k].first];
  const FloorPatch& patch = area.floors[sample_patches_[k].second];
  // Rejection sampling in the patch's box; patches fill a good part of their box, and after many
  // misses (a sliver) the vertex mean is used.
  for (int attempt = 0; attempt < 1000; ++attempt) {
    const double x = patch.box.min().x() + unit(rng) * patch.box.sizes().x();
    const double y = patch.box.min().y() + unit(rng) * patch.box.sizes().y();
    if (patch.holds(x, y)) return {{x, y, patch.height_at(x, y)}, area.cell};
  }
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& v : patch.outer_xy) mean += v;
  mean /= static_cast<double>(patch.outer_xy.size());
  return {{mean.x(), mean.y(), patch.height_at(mean.x(), mean.y())}, area.cell};
}

double FreeSpace::floor_z(int cell) const {
  if (cell < 0 || cell >= static_cast<int>(map_.cells.size())) return 0.0;
  return map_.cells[cell].floor_z;
}

}  // namespace conicloc::localizer
