#include "sim/navigation_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace conicloc::sim {
namespace {

double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

// Convex hull, counter-clockwise (Andrew's monotone chain).
maps::Ring2 convex_hull(std::vector<Eigen::Vector2d> points) {
  std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (points.size() < 3) return {};
  maps::Ring2 hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

// One level floor polygon: its outline. Several, a slope (stairs, ramps) or none: the cell's
// bounding box (the flights need not cover the landings), else the convex hull of the floors.
maps::Ring2 footprint_from_surfaces(const maps::PlaneMap& map, const maps::Cell& cell) {
  std::vector<const maps::PlanarPolygon*> floors;
  for (const int index : cell.polygons) {
    if (index < 0 || index >= static_cast<int>(map.polygons.size())) continue;
    const auto& polygon = map.polygons[index];
    if (polygon.kind == maps::SurfaceKind::Floor || polygon.kind == maps::SurfaceKind::Slope) {
      if (polygon.plane.normal.z() > 0.0) floors.push_back(&polygon);
    }
  }
  maps::Ring2 ring;
  if (floors.size() == 1 && floors.front()->kind == maps::SurfaceKind::Floor) {
    for (const auto& p : floors.front()->outer) ring.push_back(p.head<2>());
  } else if (!cell.bounds.isEmpty()) {
    const auto& lo = cell.bounds.min();
    const auto& hi = cell.bounds.max();
    ring = {{lo.x(), lo.y()}, {hi.x(), lo.y()}, {hi.x(), hi.y()}, {lo.x(), hi.y()}};
  } else if (floors.size() > 1) {
    std::vector<Eigen::Vector2d> points;
    for (const auto* polygon : floors) {
      for (const auto& p : polygon->outer) points.push_back(p.head<2>());
    }
    ring = convex_hull(points);
  }
  if (ring.size() >= 3 && maps::signed_area(ring) < 0.0) std::reverse(ring.begin(), ring.end());
  return ring;
}

Eigen::Vector2d point_inside(const maps::Ring2& ring) {
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const auto& p : ring) centroid += p;
  centroid /= static_cast<double>(ring.size());
  if (maps::ring_contains(ring, centroid)) return centroid;
  Eigen::AlignedBox2d box;
  for (const auto& p : ring) box.extend(p);
  Eigen::Vector2d best = ring.front();
  double best_distance = std::numeric_limits<double>::infinity();
  const double step = std::max(box.sizes().maxCoeff() / 50.0, 0.05);
  for (double x = box.min().x() + step / 2; x < box.max().x(); x += step) {
    for (double y = box.min().y() + step / 2; y < box.max().y(); y += step) {
      const Eigen::Vector2d p(x, y);
      if (maps::ring_contains(ring, p) && (p - centroid).norm() < best_distance) {
        best_distance = (p - centroid).norm();
        best = p;
      }
    }
  }
  return best;
}

}  // namespace

maps::PlaneMap with_navigation_geometry(const maps::PlaneMap& map) {
  maps::PlaneMap out = map;
  for (auto& cell : out.cells) {
    if (cell.footprint.size() < 3) cell.footprint = footprint_from_surfaces(out, cell);
  }
  for (auto& node : out.navigation.nodes) {
    if (node.cell < 0 || node.cell >= static_cast<int>(out.cells.size())) continue;
    const auto& cell = out.cells[node.cell];
    if (cell.footprint.size() < 3 || maps::ring_contains(cell.footprint, node.position.head<2>())) {
      continue;
    }
    const Eigen::Vector2d p = point_inside(cell.footprint);
    node.position = Eigen::Vector3d(p.x(), p.y(), cell.floor_z);
  }
  return out;
}

}  // namespace conicloc::sim
