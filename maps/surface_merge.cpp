#include "maps/surface_merge.hpp"

#include <algorithm>
#include <cmath>

#include "maps/segment_distance.hpp"

namespace conicloc::maps {
namespace {

bool boxes_touch(const PlanarPolygon& a, const PlanarPolygon& b, double margin_m) {
  const Eigen::Vector3d m = Eigen::Vector3d::Constant(margin_m);
  return (a.bounds.min().array() <= (b.bounds.max() + m).array()).all() &&
         (b.bounds.min().array() <= (a.bounds.max() + m).array()).all();
}

// Rebuilds `wall` with one more hole, keeping its attributes.
bool add_hole(PlanarPolygon& wall, const Ring3& hole_in_space) {
  Ring3 hole;
  for (const auto& p : hole_in_space) hole.push_back(wall.frame.lift(wall.frame.project(p)));
  std::vector<Ring3> holes = wall.holes;
  holes.push_back(std::move(hole));
  PlanarPolygon rebuilt;
  if (!make_planar_polygon(wall.outer, holes, rebuilt)) return false;
  rebuilt.kind = wall.kind;
  rebuilt.cell = wall.cell;
  rebuilt.storey = wall.storey;
  rebuilt.source_id = wall.source_id;
  rebuilt.two_sided = wall.two_sided;
  rebuilt.back_cell = wall.back_cell;
  rebuilt.flatness_m = std::max(rebuilt.flatness_m, wall.flatness_m);
  wall = std::move(rebuilt);
  return true;
}

}  // namespace

bool coplanar(const PlanarPolygon& a, const PlanarPolygon& b, double angle_deg, double distance_m) {
  const double cos_angle = std::cos(angle_deg * M_PI / 180.0);
  return std::abs(a.plane.normal.dot(b.plane.normal)) >= cos_angle &&
         std::abs(a.plane.signed_distance(b.centroid)) <= distance_m &&
         std::abs(b.plane.signed_distance(a.centroid)) <= distance_m;
}

bool covers(const PlanarPolygon& outer, const PlanarPolygon& inner, double tolerance_m) {
  for (const auto& p : inner.outer) {
    const Eigen::Vector2d uv = outer.frame.project(p);
    if (!ring_contains(outer.outer_uv, uv) && distance_to_ring(outer.outer_uv, uv) > tolerance_m) {
      return false;
    }
  }
  // A hole of `outer` inside `inner` (a door `inner` closes): `outer` does not cover it there.
  for (const auto& hole : outer.holes) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& p : hole) mean += p;
    mean /= static_cast<double>(hole.size());
    if (inner.contains_uv(inner.frame.project(mean))) return false;  // `inner` is solid there
  }
  return true;
}

void cut_door_openings(std::vector<PlanarPolygon>& polygons,
                       const std::vector<PlanarPolygon>& doors, MergeStats& stats) {
  std::vector<bool> removed(polygons.size(), false);
  for (const auto& door : doors) {
    for (std::size_t i = 0; i < polygons.size(); ++i) {
      PlanarPolygon& wall = polygons[i];
      if (removed[i] || !boxes_touch(wall, door, 0.05) || !coplanar(wall, door, 3.0, 0.05))
        continue;
      if (covers(door, wall, 0.05)) {  // the shell face is the door itself
        removed[i] = true;
        ++stats.door_surfaces_removed;
        continue;
      }
      const Eigen::Vector2d door_centre = wall.frame.project(door.centroid);
      if (!ring_contains(wall.outer_uv, door_centre)) continue;
      const bool already_open =
          std::any_of(wall.holes_uv.begin(), wall.holes_uv.end(),
                      [&](const Ring2& h) { return ring_contains(h, door_centre); });
      if (!already_open && add_hole(wall, door.outer)) ++stats.door_holes_cut;
    }
  }
  std::size_t kept = 0;
  for (std::size_t i = 0; i < polygons.size(); ++i) {
    if (removed[i]) continue;
    if (kept != i) polygons[kept] = std::move(polygons[i]);  // no self-move: it empties vectors
    ++kept;
  }
  polygons.resize(kept);
}

std::vector<int> merge_coplanar_faces(std::vector<PlanarPolygon>& polygons, MergeStats& stats) {
  const auto n = static_cast<int>(polygons.size());
  std::vector<int> holder(n);
  for (int i = 0; i < n; ++i) holder[i] = i;
  // Candidates sorted by bounding-box min x: a sweep keeps the pair test near-linear.
  std::vector<int> order(n);
  for (int i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return polygons[a].bounds.min().x() < polygons[b].bounds.min().x();
  });
  constexpr double kMargin_m = 0.02;
  for (int oi = 0; oi < n; ++oi) {
    const int a = order[oi];
    for (int oj = oi + 1; oj < n; ++oj) {
      const int b = order[oj];
      if (polygons[b].bounds.min().x() > polygons[a].bounds.max().x() + kMargin_m) break;
      if (holder[a] != a || holder[b] != b) continue;
      PlanarPolygon& pa = polygons[a];
      PlanarPolygon& pb = polygons[b];
      if (pa.cell == pb.cell || !boxes_touch(pa, pb, kMargin_m) || !coplanar(pa, pb)) continue;
      int keep = -1;
      int drop = -1;
      if (covers(pa, pb)) {
        keep = a, drop = b;
      } else if (covers(pb, pa)) {
        keep = b, drop = a;
      } else {
        // Overlap without cover (a long corridor wall against a short room wall): both stay.
        ++stats.partial_overlaps;
        continue;
      }
      holder[drop] = keep;
      ++stats.faces_merged;
      PlanarPolygon& kept = polygons[keep];
      if (kept.plane.normal.dot(polygons[drop].plane.normal) < 0.0 && !kept.two_sided) {
        kept.two_sided = true;
        kept.back_cell = polygons[drop].cell;
        ++stats.two_sided;
      }
      if (keep == b) break;  // `a` is gone: no more pairs with it
    }
  }
  // Resolve chains (dropped into a face that was later dropped) and compact.
  std::vector<int> new_index(n, -1);
  std::vector<PlanarPolygon> merged;
  merged.reserve(n);
  for (int i = 0; i < n; ++i) {
    if (holder[i] == i) {
      new_index[i] = static_cast<int>(merged.size());
      merged.push_back(std::move(polygons[i]));
    }
  }
  std::vector<int> result(n);
  for (int i = 0; i < n; ++i) {
    int root = i;
    while (holder[root] != root) root = holder[root];
    result[i] = new_index[root];
  }
  polygons = std::move(merged);
  return result;
}

}  // namespace conicloc::maps
