#include "maps/cell_surfaces.hpp"

#include <algorithm>
#include <cmath>

namespace conicloc::maps {
namespace {

// Newell area vector ½ Σ p_i × p_{i+1} about `center` (length = area, direction = right-hand
// normal).
Eigen::Vector3d area_vector(const Ring3& ring, const Eigen::Vector3d& center) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < ring.size(); ++i) {
    sum += (ring[i] - center).cross(ring[(i + 1) % ring.size()] - center);
  }
  return 0.5 * sum;
}

Ring3 to_map(const Ring3& ring, const MapFrame& frame) {
  Ring3 out;
  out.reserve(ring.size());
  for (const auto& p : ring) out.push_back(frame.to_map(p));
  return out;
}

// Why make_planar_polygon refused a ring.
std::string drop_reason(const Ring3& ring) {
  Ring3 distinct;
  for (const auto& p : ring) {
    if (std::none_of(distinct.begin(), distinct.end(),
                     [&](const Eigen::Vector3d& q) { return (p - q).norm() <= 1e-9; })) {
      distinct.push_back(p);
    }
  }
  if (distinct.size() < 3) return "fewer than 3 distinct vertices";
  return "zero area (collinear vertices)";
}

double cross2(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

// Andrew's monotone chain, counter-clockwise.
Ring2 convex_hull(std::vector<Eigen::Vector2d> points) {
  std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (points.size() < 3) return points;
  Ring2 hull(2 * points.size());
  std::size_t k = 0;
  for (const auto& p : points) {
    while (k >= 2 && cross2(hull[k - 2], hull[k - 1], p) <= 0) --k;
    hull[k++] = p;
  }
  for (std::size_t i = points.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross2(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

}  // namespace

bool fit_polygon(const RawPolygon& raw, const MapFrame& frame, bool reverse, PlanarPolygon& out,
                 std::map<std::string, int>& dropped) {
  Ring3 outer = to_map(raw.outer, frame);
  std::vector<Ring3> holes;
  for (const auto& hole : raw.holes) holes.push_back(to_map(hole, frame));
  if (reverse) std::reverse(outer.begin(), outer.end());
  if (!make_planar_polygon(outer, holes, out)) {
    ++dropped[drop_reason(outer)];
    return false;
  }
  out.source_id = raw.id;
  return true;
}

void add_cell_surfaces_3d(const RawCell& cell, int cell_index, const MapFrame& frame,
                          std::vector<PlanarPolygon>& out, SurfaceStats& stats) {
  Eigen::AlignedBox3d cell_box;
  for (const auto& shell : cell.shells) {
    for (const auto& polygon : shell.polygons) {
      for (const auto& p : polygon.outer) cell_box.extend(frame.to_map(p));
    }
  }
  const Eigen::Vector3d cell_center = cell_box.isEmpty() ? Eigen::Vector3d(Eigen::Vector3d::Zero())
                                                         : Eigen::Vector3d(cell_box.center());

  for (const auto& shell : cell.shells) {
    // Signed volume of a closed shell, V = ⅓ Σ (A_i n_i)·c_i (divergence theorem), about the cell
    // centre: positive when the rings' right-hand normals point out of the enclosed volume.
    double volume = 0.0;
    double area_sum = 0.0;
    for (const auto& polygon : shell.polygons) {
      const Ring3 ring = to_map(polygon.outer, frame);
      if (ring.size() < 3) continue;
      const Eigen::Vector3d a = area_vector(ring, cell_center);
      volume += a.dot(ring.front() - cell_center) / 3.0;
      area_sum += a.norm();
    }
    // Closed when |V| is a fair share of what its area can enclose (a cube: V = (A/6)^1.5).
    const double cube_volume = std::pow(area_sum / 6.0, 1.5);
    const bool closed = area_sum > 0.0 && std::abs(volume) > 0.05 * cube_volume;
    if (!closed) ++stats.open_shells;
    // Exterior shell: free space is inside, so inward normals (V < 0 as written is right).
    // Interior shell (a void): free space is outside the void, so normals out of it (V > 0).
    const bool wants_positive = shell.interior;
    const bool flip_shell = closed && ((volume > 0.0) != wants_positive);
    if (flip_shell) ++stats.shells_flipped;

    for (const auto& raw : shell.polygons) {
      PlanarPolygon polygon;
      if (!fit_polygon(raw, frame, flip_shell, polygon, stats.dropped)) continue;
      if (!closed) {
        // Open surface set: face each polygon towards the cell's centre.
        const bool towards = polygon.plane.signed_distance(cell_center) >= 0.0;
        if (towards == shell.interior) fit_polygon(raw, frame, true, polygon, stats.dropped);
      }
      polygon.cell = cell_index;
      out.push_back(std::move(polygon));
    }
  }
}

void add_cell_surfaces_2d(const RawCell& cell, int cell_index, const MapFrame& frame,
                          double height_m, std::vector<PlanarPolygon>& out, SurfaceStats& stats) {
  for (const auto& raw : cell.footprints_2d) {
    PlanarPolygon floor;
    if (!fit_polygon(raw, frame, false, floor, stats.dropped)) continue;
    // A footprint is level: make it face up (floor), then build the ceiling and walls from it.
    if (floor.plane.normal.z() < 0.0) fit_polygon(raw, frame, true, floor, stats.dropped);
    const Eigen::Vector3d up = height_m * Eigen::Vector3d::UnitZ();
    Ring3 ceiling_outer = floor.outer;
    for (auto& p : ceiling_outer) p += up;
    std::reverse(ceiling_outer.begin(), ceiling_outer.end());  // faces down
    std::vector<Ring3> ceiling_holes = floor.holes;
    for (auto& hole : ceiling_holes) {
      for (auto& p : hole) p += up;
    }
    PlanarPolygon ceiling;
    make_planar_polygon(ceiling_outer, ceiling_holes, ceiling);

    // Walls: one rectangle per edge, facing the interior, which lies left of each edge of the
    // counter-clockwise outer ring and right of each edge of the clockwise holes.
    auto add_walls = [&](const Ring3& ring) {
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const Eigen::Vector3d& a = ring[i];
        const Eigen::Vector3d& b = ring[(i + 1) % ring.size()];
        const Eigen::Vector3d inward = Eigen::Vector3d::UnitZ().cross(b - a);
        PlanarPolygon wall;
        if (!make_planar_polygon({a, b, b + up, a + up}, {}, wall)) {
          ++stats.dropped["zero-length footprint edge"];
          continue;
        }
        if (wall.plane.normal.dot(inward) < 0.0)
          make_planar_polygon({a, a + up, b + up, b}, {}, wall);
        wall.cell = cell_index;
        wall.source_id = raw.id;
        out.push_back(std::move(wall));
      }
    };
    add_walls(floor.outer);
    for (const auto& hole : floor.holes) add_walls(hole);

    floor.cell = cell_index;
    ceiling.cell = cell_index;
    ceiling.source_id = raw.id;
    out.push_back(std::move(floor));
    out.push_back(std::move(ceiling));
  }
}

Ring2 cell_footprint(const std::vector<const PlanarPolygon*>& surfaces) {
  const PlanarPolygon* best = nullptr;
  for (const PlanarPolygon* polygon : surfaces) {
    if (polygon->plane.normal.z() > 0.5 && (best == nullptr || polygon->area > best->area)) {
      best = polygon;
    }
  }
  Ring2 ring;
  if (best != nullptr) {
    for (const auto& p : best->outer) ring.emplace_back(p.x(), p.y());
    if (signed_area(ring) < 0.0) std::reverse(ring.begin(), ring.end());
    return ring;
  }
  std::vector<Eigen::Vector2d> points;
  for (const PlanarPolygon* polygon : surfaces) {
    for (const auto& p : polygon->outer) points.emplace_back(p.x(), p.y());
  }
  return convex_hull(std::move(points));
}

Eigen::Vector2d point_inside(const Ring2& ring) {
  if (ring.empty()) return Eigen::Vector2d::Zero();
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : ring) mean += p;
  mean /= static_cast<double>(ring.size());
  if (ring_contains(ring, mean)) return mean;
  // Horizontal chord through the mean: crossings sorted, inside between pairs (even-odd).
  std::vector<double> xs;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const auto& a = ring[i];
    const auto& b = ring[j];
    if ((a.y() > mean.y()) != (b.y() > mean.y())) {
      xs.push_back(a.x() + (mean.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y()));
    }
  }
  std::sort(xs.begin(), xs.end());
  double best_width = -1.0;
  Eigen::Vector2d best = mean;
  for (std::size_t i = 0; i + 1 < xs.size(); i += 2) {
    if (xs[i + 1] - xs[i] > best_width) {
      best_width = xs[i + 1] - xs[i];
      best = {0.5 * (xs[i] + xs[i + 1]), mean.y()};
    }
  }
  return best;
}

}  // namespace conicloc::maps
