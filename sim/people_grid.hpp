#pragma once
// Which of a building's people may stand near a point: a uniform grid over the boxes of their
// walks, so a firing visits the cells around the sensor instead of every person in the building.

#include <Eigen/Geometry>
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace conicloc::sim {

class PeopleGrid {
 public:
  PeopleGrid() = default;
  /// Over `walks[i]`: the xy box person i stays in (its walk from → to, widened by its radius).
  explicit PeopleGrid(const std::vector<Eigen::AlignedBox2d>& walks);

  /// Calls visit(i) once for every person whose walk box lies within `distance` of `point`
  /// (and for some a little farther: those sharing a grid cell with the query's square), in no
  /// particular order.
  template <typename Visit>
  void for_each_near(const Eigen::Vector2d& point, double distance, Visit&& visit) const {
    CellRange q;
    if (!query_cells(point, distance, q)) return;
    for (int y = q.y0; y <= q.y1; ++y) {
      for (int x = q.x0; x <= q.x1; ++x) {
        const std::size_t c = static_cast<std::size_t>(y) * columns_ + x;
        for (std::uint32_t j = first_[c]; j < first_[c + 1]; ++j) {
          const std::uint32_t i = people_[j];
          // A walk spanning several of the visited cells is visited from the first only.
          const CellRange& r = walk_cells_[i];
          if (x == std::max(r.x0, q.x0) && y == std::max(r.y0, q.y0)) visit(std::size_t{i});
        }
      }
    }
  }

 private:
  struct CellRange {
    int x0, y0, x1, y1;  ///< inclusive
  };
  CellRange cells_of(const Eigen::AlignedBox2d& box) const;
  /// The cells of the square of half-width `distance` about `point`; false if it meets none.
  bool query_cells(const Eigen::Vector2d& point, double distance, CellRange& cells) const;

  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double cell_m_ = 1.0;
  int columns_ = 0, rows_ = 0;
  std::vector<CellRange> walk_cells_;  ///< the cells each walk box spans
  std::vector<std::uint32_t> first_;   ///< cell c holds people_[first_[c] .. first_[c + 1])
  std::vector<std::uint32_t> people_;  ///< person indices, cell by cell
};

}  // namespace conicloc::sim
