#pragma once
// A floor plan as a 2D likelihood field with a max-pyramid, for a branch-and-bound search of
// where a scan fits (plan_search.hpp; the precomputation grids of Hess et al., "Real-Time Loop
// Closure in 2D LIDAR SLAM", ICRA 2016).
//
// Level 0 holds, per cell of side `resolution_m`, how well a return there fits a wall:
//   f(c) = 255 · exp(−d(c)² / 2σ²),  d(c) the distance from the cell's centre to the nearest wall
// segment (0 beyond 3σ). Level k holds the maximum of level 0 over the 2^k × 2^k cells from c on:
//   L_k(i, j) = max{ L_0(i + a, j + b) : 0 ≤ a, b < 2^k },
// so Σ_p L_k(c_p + t) bounds the score of every translation in [t, t + 2^k)² at once (cells
// outside the grid count 0).

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "maps/polygon_section.hpp"

namespace conicloc::localizer {

class PlanField {
 public:
  /// The field of `walls` (their xy) over `extent` (map frame, metres), with `levels` levels
  /// (level 0 and levels − 1 coarser ones), and `padding_cells` cells of 0 around it: a sum
  /// over cells at offsets up to that far from the extent then needs no check per cell (cells()).
  /// Precondition: resolution_m, sigma_m > 0, levels ≥ 1.
  PlanField(const std::vector<maps::SectionSegment>& walls, const Eigen::AlignedBox2d& extent,
            double resolution_m, double sigma_m, int levels, int padding_cells = 0);

  int width() const { return width_; }
  int height() const { return height_; }
  int levels() const { return static_cast<int>(levels_.size()); }
  double resolution_m() const { return resolution_m_; }
  /// The corner of cell (0, 0): cell (i, j) covers origin + [i, i + 1) × [j, j + 1) · resolution.
  const Eigen::Vector2d& origin() const { return origin_; }

  /// L_level(i, j); 0 outside the grid. A window that starts below the grid (i or j in
  /// (−2^level, 0)) overlaps its first cells: it gets the window from 0 on, which holds its part
  /// inside the grid — a bound as the search needs it, not the exact maximum.
  std::uint8_t at(int level, int i, int j) const {
    const int size = 1 << level;
    if (i <= -size || j <= -size || i >= width_ || j >= height_) return 0;
    return levels_[static_cast<std::size_t>(level)]
                  [static_cast<std::size_t>(std::max(j, 0)) * static_cast<std::size_t>(width_) +
                   static_cast<std::size_t>(std::max(i, 0))];
  }

  /// Level `level`'s cells row by row, width() to a row: L_level(i, j) at [j·width() + i], for
  /// callers that keep (i, j) inside the grid themselves.
  const std::uint8_t* cells(int level) const {
    return levels_[static_cast<std::size_t>(level)].data();
  }

  /// Bytes held by all levels.
  std::size_t memory_bytes() const;

 private:
  /// Paints `wall` into level 0's cells inside `inner` (the extent without the padding).
  void paint(const maps::SectionSegment& wall, double sigma_m, const Eigen::AlignedBox2i& inner);
  void build_pyramid(int levels);

  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double resolution_m_ = 0.1;
  int width_ = 0;
  int height_ = 0;
  std::vector<std::vector<std::uint8_t>> levels_;
};

}  // namespace conicloc::localizer
