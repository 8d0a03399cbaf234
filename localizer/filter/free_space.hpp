#pragma once
// The free space of a building for the filter: the navigable cells' floors on every storey.
// Answers "which cell (and floor) is under this pose" and draws poses uniformly over the floor
// area, for global initialisation and recovery. The floor of a cell is its walkable surfaces
// (floors, ramps, stair flights modelled as slopes), so its height varies with x, y on a stair.

#include <Eigen/Core>
#include <random>
#include <utility>
#include <vector>

#include "maps/plane_map.hpp"

namespace conicloc::localizer {

class FreeSpace {
 public:
  /// Keeps a reference to `map` (must outlive this). A cell's free space is the plan view of its
  /// walkable surfaces (all of them: a stair's landings and flight); a cell without any uses its
  /// footprint, else the xy rectangle of its bounds, at its floor_z.
  explicit FreeSpace(const maps::PlaneMap& map);

  /// True when the map has at least one navigable cell of positive floor area.
  bool empty() const { return total_area_m2_ <= 0.0; }
  double total_area_m2() const { return total_area_m2_; }

  /// The navigable cell whose floors hold (x, y) in plan view (edges included) and whose floor at
  /// (x, y) is the highest one not above `z_m` + `floor_tolerance_m` (the floor the sensor stands
  /// over); if only cells on storeys above hold (x, y), the lowest of those. −1 when no navigable
  /// cell holds (x, y).
  int cell_at(double x, double y, double z_m, double floor_tolerance_m = 0.5) const;

  /// Fast path for a particle that was in `hint_cell`: that cell when it still holds (x, y),
  /// else cell_at().
  int cell_at(double x, double y, double z_m, int hint_cell) const;

  /// Height (m, map frame) of the floor of `cell` under (x, y): the walkable surface of the cell
  /// (upward normal within 60° of vertical, at least 1 m below the cell's top) whose outline
  /// holds (x, y) in plan view, its plane z = −(n_x x + n_y y + d) / n_z. Where several hold it,
  /// the highest not above `z_hint_m` + 0.5 m (else the lowest); where none does (a seam, a
  /// hole), the nearest one's plane clamped to its height range. A cell without walkable
  /// surfaces, or an unknown cell: floor_z(cell).
  double floor_z_at(int cell, double x, double y, double z_hint_m) const;

  /// A point (x, y, floor z at x, y) drawn uniformly over the floor area (plan view) of all
  /// navigable cells, and the cell it lies in.
  struct Sample {
    Eigen::Vector3d point_on_floor;
    int cell = -1;
  };
  Sample sample(std::mt19937_64& rng) const;

  /// The lowest floor of `cell` (PlaneMap's Cell::floor_z); 0 for an unknown cell.
  double floor_z(int cell) const;

 private:
  /// One walkable surface of a cell in plan view: z = slope_x·x + slope_y·y + z0 over its outline.
  struct FloorPatch {
    maps::Ring2 outer_xy;
    std::vector<maps::Ring2> holes_xy;
    Eigen::AlignedBox2d box;
    double slope_x = 0.0;
    double slope_y = 0.0;
    double z0 = 0.0;
    double min_z = 0.0;
    double max_z = 0.0;
    double height_at(double x, double y) const { return slope_x * x + slope_y * y + z0; }
    bool holds(double x, double y) const;
  };
  struct CellArea {
    int cell = -1;
    Eigen::AlignedBox2d box;  ///< of all floors
    double floor_z = 0.0;
    std::vector<FloorPatch> floors;
    double lowest_floor_z = 0.0, highest_floor_z = 0.0;  ///< over its floors' heights
  };
  static void add_floor_patches(const maps::PlaneMap& map, int cell, CellArea& area);
  bool holds(const CellArea& area, double x, double y) const;
  double floor_height(const CellArea& area, double x, double y, double z_hint_m) const;

  const maps::PlaneMap& map_;
  std::vector<CellArea> areas_;
  std::vector<double> cumulative_area_m2_;  ///< for area-proportional choice of a floor patch
  std::vector<std::pair<int, int>> sample_patches_;  ///< (areas_ index, floors index) per entry
  std::vector<int> area_of_cell_;                    ///< PlaneMap cell index -> areas_ index or -1
  double total_area_m2_ = 0.0;

  // A uniform xy grid of candidate areas, so cell_at() tests a handful of cells.
  Eigen::Vector2d grid_min_ = Eigen::Vector2d::Zero();
  double grid_cell_m_ = 1.0;
  int grid_nx_ = 0;
  int grid_ny_ = 0;
  std::vector<std::vector<int>> grid_;
};

}  // namespace conicloc::localizer
