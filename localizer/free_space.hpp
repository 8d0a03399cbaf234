#pragma once
// The free space of a building for the filter: the navigable cells' footprints on every storey.
// Answers "which cell (and floor) is under this pose" and draws poses uniformly over the floor
// area, for global initialisation and recovery.

#include <Eigen/Core>
#include <random>
#include <vector>

#include "maps/plane_map.hpp"

namespace conicloc::localizer {

class FreeSpace {
 public:
  /// Keeps a reference to `map` (must outlive this). Cells whose footprint is empty use the
  /// xy rectangle of their bounds.
  explicit FreeSpace(const maps::PlaneMap& map);

  /// True when the map has at least one navigable cell of positive floor area.
  bool empty() const { return total_area_m2_ <= 0.0; }
  double total_area_m2() const { return total_area_m2_; }

  /// The navigable cell whose footprint holds (x, y) and whose floor is the highest one not above
  /// `z_m` + `floor_tolerance_m` (the floor the sensor stands over); if the footprint holds (x, y)
  /// only on storeys above, the lowest of those. −1 when no navigable cell holds (x, y).
  int cell_at(double x, double y, double z_m, double floor_tolerance_m = 0.5) const;

  /// Fast path for a particle that was in `hint_cell`: that cell when it still holds (x, y),
  /// else cell_at().
  int cell_at(double x, double y, double z_m, int hint_cell) const;

  /// A point (x, y, floor_z) drawn uniformly over the floor area of all navigable cells, and the
  /// cell it lies in.
  struct Sample {
    Eigen::Vector3d point_on_floor;
    int cell = -1;
  };
  Sample sample(std::mt19937_64& rng) const;

  double floor_z(int cell) const;

 private:
  struct CellArea {
    int cell = -1;
    maps::Ring2 footprint;
    Eigen::AlignedBox2d box;
    double floor_z = 0.0;
  };
  bool holds(const CellArea& area, double x, double y) const;

  const maps::PlaneMap& map_;
  std::vector<CellArea> areas_;
  std::vector<double> cumulative_area_m2_;  ///< for area-proportional choice of a cell
  std::vector<int> area_of_cell_;           ///< PlaneMap cell index -> areas_ index or -1
  double total_area_m2_ = 0.0;

  // A uniform xy grid of candidate areas, so cell_at() tests a handful of footprints.
  Eigen::Vector2d grid_min_ = Eigen::Vector2d::Zero();
  double grid_cell_m_ = 1.0;
  int grid_nx_ = 0;
  int grid_ny_ = 0;
  std::vector<std::vector<int>> grid_;
};

}  // namespace conicloc::localizer
