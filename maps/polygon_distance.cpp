// Exact distances from a planar polygon with holes to a point and to an axis-aligned box.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "maps/plane_index.hpp"

namespace conicloc::maps {
namespace {

// Closest point of segment [a, b] to p, all in the plane's uv coordinates.
Eigen::Vector2d closest_on_segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                   const Eigen::Vector2d& p) {
  const Eigen::Vector2d ab = b - a;
  const double length2 = ab.squaredNorm();
  if (length2 <= 0.0) return a;
  const double t = std::clamp((p - a).dot(ab) / length2, 0.0, 1.0);
  return a + t * ab;
}

// Squared distance from segment a + t·d, t ∈ [0, 1], to a non-empty box. Per axis the squared
// excess over the slab [lo, hi] is 0 inside and (a_i + t d_i - bound)² outside, so the total is a
// quadratic in t between the (at most 6) slab crossings; each piece is minimised in closed form.
double segment_box_squared_distance(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                    const Eigen::AlignedBox3d& box) {
  const Eigen::Vector3d d = b - a;
  std::array<double, 8> breaks{};
  std::size_t n_breaks = 0;
  breaks[n_breaks++] = 0.0;
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0.0) continue;
    for (const double bound : {box.min()[i], box.max()[i]}) {
      const double t = (bound - a[i]) / d[i];
      if (t > 0.0 && t < 1.0) breaks[n_breaks++] = t;
    }
  }
  breaks[n_breaks++] = 1.0;
  // Insertion sort of at most 8 values (std::sort on a short std::array trips -Warray-bounds).
  for (std::size_t i = 1; i < n_breaks; ++i) {
    for (std::size_t j = i; j > 0 && breaks[j - 1] > breaks[j]; --j)
      std::swap(breaks[j - 1], breaks[j]);
  }

  double best = std::numeric_limits<double>::infinity();
  auto consider = [&](double t) { best = std::min(best, box.squaredExteriorDistance(a + t * d)); };
  for (std::size_t k = 0; k + 1 < n_breaks; ++k) {
    const double t0 = breaks[k];
    const double t1 = breaks[k + 1];
    consider(t0);
    const Eigen::Vector3d mid = a + 0.5 * (t0 + t1) * d;
    double quadratic = 0.0;  // coefficient of t²
    double linear = 0.0;     // coefficient of t
    for (int i = 0; i < 3; ++i) {
      double excess = 0.0;  // a_i - bound for the violated bound, on this piece
      if (mid[i] < box.min()[i]) {
        excess = a[i] - box.min()[i];
      } else if (mid[i] > box.max()[i]) {
        excess = a[i] - box.max()[i];
      } else {
        continue;
      }
      quadratic += d[i] * d[i];
      linear += 2.0 * excess * d[i];
    }
    if (quadratic > 0.0) consider(std::clamp(-linear / (2.0 * quadratic), t0, t1));
  }
  consider(1.0);
  return best;
}

template <typename Visit>
void for_each_edge(const PlanarPolygon& polygon, Visit&& visit) {
  auto ring_edges = [&](const Ring3& ring) {
    for (std::size_t i = 0; i < ring.size(); ++i) visit(ring[i], ring[(i + 1) % ring.size()]);
  };
  ring_edges(polygon.outer);
  for (const auto& hole : polygon.holes) ring_edges(hole);
}

}  // namespace

Eigen::Vector3d closest_point(const PlanarPolygon& polygon, const Eigen::Vector3d& point) {
  // |p - x|² = h² + |uv(p) - uv(x)|² for x on the plane (h: height above it), so the closest
  // point is the closest one in uv: the projection itself when inside, else on a ring edge.
  const Eigen::Vector2d uv = polygon.frame.project(point);
  if (polygon.contains_uv(uv)) return polygon.frame.lift(uv);
  Eigen::Vector2d best = uv;
  double best_distance2 = std::numeric_limits<double>::infinity();
  auto ring_edges = [&](const Ring2& ring) {
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Eigen::Vector2d candidate =
          closest_on_segment(ring[i], ring[(i + 1) % ring.size()], uv);
      const double distance2 = (candidate - uv).squaredNorm();
      if (distance2 < best_distance2) {
        best_distance2 = distance2;
        best = candidate;
      }
    }
  };
  ring_edges(polygon.outer_uv);
  for (const auto& hole : polygon.holes_uv) ring_edges(hole);
  return polygon.frame.lift(best);
}

double distance_to_box(const PlanarPolygon& polygon, const Eigen::AlignedBox3d& box) {
  if (box.isEmpty()) return std::numeric_limits<double>::infinity();

  // Boundary part: the closest pair may have its polygon point on a ring edge.
  double best2 = std::numeric_limits<double>::infinity();
  for_each_edge(polygon, [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    best2 = std::min(best2, segment_box_squared_distance(a, b, box));
  });
  if (best2 == 0.0) return 0.0;

  // Interior part. A minimum at an interior point of the polygon is a minimum of the (convex)
  // box distance over the whole plane; that set is convex, so if the point found below lies
  // outside the polygon, the minimum set crosses a ring edge and the boundary part has it.
  Eigen::Vector3d nearest_corner = box.min();
  Eigen::Vector3d farthest_corner = box.min();
  double s_min = std::numeric_limits<double>::infinity();
  double s_max = -std::numeric_limits<double>::infinity();
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d corner = box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(k));
    const double s = polygon.plane.signed_distance(corner);
    if (s < s_min) {
      s_min = s;
      nearest_corner = corner;
    }
    if (s > s_max) {
      s_max = s;
      farthest_corner = corner;
    }
  }
  if (s_min <= 0.0 && s_max >= 0.0) {
    // The plane cuts the box: a point of the section, on the segment between the extreme corners.
    const double t = s_max > s_min ? -s_min / (s_max - s_min) : 0.0;
    const Eigen::Vector3d section_point = nearest_corner + t * (farthest_corner - nearest_corner);
    if (polygon.contains_uv(polygon.frame.project(section_point))) return 0.0;
  } else {
    const bool above = s_min > 0.0;
    const Eigen::Vector3d& corner = above ? nearest_corner : farthest_corner;
    const double height = above ? s_min : -s_max;
    if (polygon.contains_uv(polygon.frame.project(corner)))
      best2 = std::min(best2, height * height);
  }
  return std::sqrt(best2);
}

}  // namespace conicloc::maps
