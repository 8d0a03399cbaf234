// Ear clipping with hole bridging (D. Eberly, "Triangulation by Ear Clipping", Geometric Tools,
// 2002): each hole, rightmost first, is joined to the outer ring by a bridge from its rightmost
// vertex M to a vertex visible from M, which turns the polygon into one weakly simple ring; that
// ring is then cut into triangles by repeatedly removing an "ear" (a convex vertex whose triangle
// holds no other vertex).
#include "maps/polygon_triangulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace conicloc::maps {
namespace {

using Point = Eigen::Vector2d;

double cross(const Point& a, const Point& b, const Point& c) {
  return (b - a).x() * (c - b).y() - (b - a).y() * (c - b).x();
}

// Inclusive: points on an edge count as inside (a diagonal through a vertex is rejected).
bool in_triangle(const Point& p, const Point& a, const Point& b, const Point& c) {
  const double d1 = cross(a, b, p);
  const double d2 = cross(b, c, p);
  const double d3 = cross(c, a, p);
  const bool has_negative = d1 < 0 || d2 < 0 || d3 < 0;
  const bool has_positive = d1 > 0 || d2 > 0 || d3 > 0;
  return !(has_negative && has_positive);
}

double ring_area(const std::vector<Point>& points, const std::vector<int>& ring) {
  double twice = 0.0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Point& a = points[static_cast<std::size_t>(ring[i])];
    const Point& b = points[static_cast<std::size_t>(ring[(i + 1) % ring.size()])];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * twice;
}

// True when direction `to` leaves vertex `at` into the polygon's interior, i.e. lies in the
// counter-clockwise sector from the outgoing edge (to `next`) to the incoming one (to `prev`).
bool in_interior_sector(const Point& prev, const Point& at, const Point& next, const Point& to) {
  auto angle = [](const Point& v) { return std::atan2(v.y(), v.x()); };
  auto ccw_from = [&](double base, double a) {
    double d = a - base;
    while (d < 0) d += 2 * M_PI;
    while (d >= 2 * M_PI) d -= 2 * M_PI;
    return d;
  };
  const double base = angle(next - at);
  return ccw_from(base, angle(to - at)) <= ccw_from(base, angle(prev - at));
}

using Loop = std::vector<int>;  // indices into the polygon's vertices

// Cuts a ring at every vertex it revisits into simple loops: real files write a polygon with a
// window as ONE ring (around the window, across to the outline, around it, back), and such
// keyhole rings are not simple. What is left after the cuts is made of the jumps between the
// loops: a back-and-forth (2 vertices) or, when the ring jumps loop to loop and then straight
// back to the first, a "loop" whose every vertex is a junction. Neither bounds any material, so
// both are dropped; a leftover with other vertices is a real part (a figure-eight's lobe).
std::vector<Loop> split_at_repeats(const std::vector<Point>& points, const Loop& ring,
                                   double tolerance2) {
  std::vector<Loop> loops;
  std::vector<int> junctions;
  Loop path;
  for (const int i : ring) {
    const Point& p = points[static_cast<std::size_t>(i)];
    auto seen = std::find_if(path.begin(), path.end(), [&](int j) {
      return (points[static_cast<std::size_t>(j)] - p).squaredNorm() <= tolerance2;
    });
    if (seen == path.end()) {
      path.push_back(i);
      continue;
    }
    junctions.push_back(*seen);
    loops.emplace_back(seen, path.end());  // closes back at *seen, where p is
    path.erase(seen + 1, path.end());
  }
  const bool only_jumps = std::all_of(path.begin(), path.end(), [&](int i) {
    return std::find(junctions.begin(), junctions.end(), i) != junctions.end();
  });
  if (!only_jumps) loops.push_back(std::move(path));
  return loops;
}

class Triangulator {
 public:
  /// `outer` counter-clockwise, `holes` clockwise, all simple.
  Triangulator(const std::vector<Point>& points, Loop outer, std::vector<Loop> holes, double scale2)
      : points_(points), ring_(std::move(outer)), scale2_(scale2) {
    // Rightmost hole first, so every bridge only crosses rings already merged.
    auto max_x = [&](const Loop& ring) {
      double m = -std::numeric_limits<double>::infinity();
      for (int i : ring) m = std::max(m, at(i).x());
      return m;
    };
    std::sort(holes.begin(), holes.end(),
              [&](const auto& a, const auto& b) { return max_x(a) > max_x(b); });
    if (ring_.size() >= 3) {
      for (const auto& hole : holes) bridge(hole);
    }
  }

  std::vector<Triangle> clip_ears() const;

 private:
  const Point& at(int index) const { return points_[static_cast<std::size_t>(index)]; }
  void bridge(const Loop& hole);

  const std::vector<Point>& points_;
  Loop ring_;            // merged ring, counter-clockwise; bridge vertices appear twice
  double scale2_ = 0.0;  // squared size of the polygon, for relative tolerances
};

void Triangulator::bridge(const Loop& hole) {
  // M: the hole's rightmost vertex.
  std::size_t m_pos = 0;
  for (std::size_t i = 1; i < hole.size(); ++i) {
    if (at(hole[i]).x() > at(hole[m_pos]).x()) m_pos = i;
  }
  const Point m = at(hole[m_pos]);

  // Nearest hit of the ray M + t·(1, 0), t >= 0, with the merged ring: a vertex or an edge.
  const std::size_t n = ring_.size();
  double best_x = std::numeric_limits<double>::infinity();
  std::ptrdiff_t visible = -1;  // ring position of the candidate visible vertex
  Point hit = m;
  for (std::size_t i = 0; i < n; ++i) {
    const Point& a = at(ring_[i]);
    const Point& b = at(ring_[(i + 1) % n]);
    if (a.y() == m.y() && a.x() >= m.x() && a.x() <= best_x) {
      best_x = a.x();
      visible = static_cast<std::ptrdiff_t>(i);
      hit = a;
      continue;
    }
    if ((a.y() < m.y()) == (b.y() < m.y()) || b.y() == m.y()) continue;
    const double x = a.x() + (m.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
    if (x < m.x() || x >= best_x) continue;
    best_x = x;
    hit = Point(x, m.y());
    visible = static_cast<std::ptrdiff_t>(a.x() > b.x() ? i : (i + 1) % n);
  }
  if (visible < 0) return;  // hole outside the outer ring: invalid input, leave it out

  // If other ring vertices lie inside triangle (M, hit, P), the visible one is the reflex vertex
  // among them with the smallest angle to the ray (then the nearest).
  const Point p = at(ring_[static_cast<std::size_t>(visible)]);
  if (hit != p) {
    double best_angle = std::numeric_limits<double>::infinity();
    double best_distance = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i) {
      const Point& r = at(ring_[i]);
      if (r == p) continue;
      const Point& prev = at(ring_[(i + n - 1) % n]);
      const Point& next = at(ring_[(i + 1) % n]);
      if (cross(prev, r, next) > 0) continue;  // only reflex vertices can block
      if (!in_triangle(r, m, hit, p) && !in_triangle(r, m, p, hit)) continue;
      const Point d = r - m;
      const double angle = std::atan2(std::abs(d.y()), d.x());
      if (angle < best_angle || (angle == best_angle && d.norm() < best_distance)) {
        best_angle = angle;
        best_distance = d.norm();
        visible = static_cast<std::ptrdiff_t>(i);
      }
    }
  }
  // A vertex used by an earlier bridge appears twice: take the copy whose interior sector holds M.
  const int visible_index = ring_[static_cast<std::size_t>(visible)];
  for (std::size_t i = 0; i < n; ++i) {
    if (ring_[i] != visible_index) continue;
    if (in_interior_sector(at(ring_[(i + n - 1) % n]), at(ring_[i]), at(ring_[(i + 1) % n]), m)) {
      visible = static_cast<std::ptrdiff_t>(i);
      break;
    }
  }

  // Splice: ..., P, M, hole..., M, P, ...
  std::vector<int> merged;
  merged.reserve(n + hole.size() + 2);
  merged.insert(merged.end(), ring_.begin(), ring_.begin() + visible + 1);
  for (std::size_t k = 0; k <= hole.size(); ++k) merged.push_back(hole[(m_pos + k) % hole.size()]);
  merged.push_back(visible_index);
  merged.insert(merged.end(), ring_.begin() + visible + 1, ring_.end());
  ring_ = std::move(merged);
}

std::vector<Triangle> Triangulator::clip_ears() const {
  std::vector<Triangle> triangles;
  const std::size_t n = ring_.size();
  if (n < 3) return triangles;
  std::vector<std::size_t> prev(n), next(n);
  for (std::size_t i = 0; i < n; ++i) {
    prev[i] = (i + n - 1) % n;
    next[i] = (i + 1) % n;
  }
  const double flat = 1e-12 * scale2_;  // |cross| below this: collinear, no area to cut
  auto point = [&](std::size_t pos) -> const Point& { return at(ring_[pos]); };
  auto remove = [&](std::size_t pos) {
    next[prev[pos]] = next[pos];
    prev[next[pos]] = prev[pos];
  };
  auto is_ear = [&](std::size_t pos) {
    const Point& a = point(prev[pos]);
    const Point& b = point(pos);
    const Point& c = point(next[pos]);
    for (std::size_t k = next[next[pos]]; k != prev[pos]; k = next[k]) {
      const Point& q = point(k);
      if (q == a || q == b || q == c) continue;  // bridge copies of the triangle's own corners
      if (in_triangle(q, a, b, c)) return false;
    }
    return true;
  };

  std::size_t remaining = n;
  std::size_t pos = 0;
  std::size_t since_clip = 0;
  while (remaining > 3) {
    const double turn = cross(point(prev[pos]), point(pos), point(next[pos]));
    if (std::abs(turn) <= flat) {  // collinear vertex or zero-width spike: drop it
      remove(pos);
      --remaining;
      pos = prev[pos];
      since_clip = 0;
      continue;
    }
    if (turn > 0 && is_ear(pos)) {
      triangles.push_back({ring_[prev[pos]], ring_[pos], ring_[next[pos]]});
      remove(pos);
      --remaining;
      pos = prev[pos];
      since_clip = 0;
      continue;
    }
    pos = next[pos];
    if (++since_clip > remaining) {
      // No ear: only invalid (self-intersecting) input gets here. Cut the first convex vertex
      // anyway, or drop a vertex, so the loop always ends.
      std::size_t k = pos;
      for (std::size_t step = 0; step < remaining; ++step, k = next[k]) {
        if (cross(point(prev[k]), point(k), point(next[k])) > 0) break;
      }
      if (cross(point(prev[k]), point(k), point(next[k])) > 0) {
        triangles.push_back({ring_[prev[k]], ring_[k], ring_[next[k]]});
      }
      remove(k);
      --remaining;
      pos = next[k];
      since_clip = 0;
    }
  }
  if (cross(point(prev[pos]), point(pos), point(next[pos])) > flat) {
    triangles.push_back({ring_[prev[pos]], ring_[pos], ring_[next[pos]]});
  }
  return triangles;
}

}  // namespace

std::vector<Triangle> triangulate(const Ring2& outer, const std::vector<Ring2>& holes) {
  if (outer.size() < 3) return {};
  std::vector<Point> points(outer.begin(), outer.end());
  Eigen::AlignedBox2d extent;
  for (const auto& p : outer) extent.extend(p);
  const double scale2 = extent.diagonal().squaredNorm();
  const double tolerance2 = 1e-20 * scale2;  // "the same vertex": equal to ~1e-10 of the size
  const double min_area = 1e-14 * scale2;

  // Loops of the outer ring: those turning like the largest are outlines (several if the ring
  // is a multi-part keyhole), the others holes; loops of hole rings are holes.
  Loop outer_ring(outer.size());
  for (std::size_t i = 0; i < outer.size(); ++i) outer_ring[i] = static_cast<int>(i);
  const auto outer_loops = split_at_repeats(points, outer_ring, tolerance2);
  double main_area = 0.0;
  for (const auto& loop : outer_loops) {
    const double a = ring_area(points, loop);
    if (std::abs(a) > std::abs(main_area)) main_area = a;
  }
  if (std::abs(main_area) <= min_area) return {};
  std::vector<Loop> outlines;
  std::vector<Loop> hole_loops;
  auto add_hole = [&](Loop loop) {
    const double a = ring_area(points, loop);
    if (loop.size() < 3 || std::abs(a) <= min_area) return;
    if (a > 0) std::reverse(loop.begin(), loop.end());  // holes run clockwise
    hole_loops.push_back(std::move(loop));
  };
  for (auto loop : outer_loops) {
    const double a = ring_area(points, loop);
    if (loop.size() < 3 || std::abs(a) <= min_area) continue;
    if ((a > 0) != (main_area > 0)) {
      add_hole(std::move(loop));
    } else {
      if (a < 0) std::reverse(loop.begin(), loop.end());
      outlines.push_back(std::move(loop));
    }
  }
  for (const auto& hole : holes) {
    Loop ring;
    for (const auto& p : hole) {
      ring.push_back(static_cast<int>(points.size()));
      points.push_back(p);
    }
    for (auto& loop : split_at_repeats(points, ring, tolerance2)) add_hole(std::move(loop));
  }

  // Each hole goes to the outline holding most of its vertices (the first one if none does).
  std::vector<std::vector<Loop>> holes_of(outlines.size());
  for (auto& hole : hole_loops) {
    std::size_t best = 0;
    std::size_t best_count = 0;
    for (std::size_t k = 0; k < outlines.size(); ++k) {
      Ring2 ring;
      for (const int i : outlines[k]) ring.push_back(points[static_cast<std::size_t>(i)]);
      std::size_t count = 0;
      for (const int i : hole) count += ring_contains(ring, points[static_cast<std::size_t>(i)]);
      if (count > best_count) {
        best_count = count;
        best = k;
      }
    }
    holes_of[best].push_back(std::move(hole));
  }

  std::vector<Triangle> triangles;
  for (std::size_t k = 0; k < outlines.size(); ++k) {
    const auto part =
        Triangulator(points, std::move(outlines[k]), std::move(holes_of[k]), scale2).clip_ears();
    triangles.insert(triangles.end(), part.begin(), part.end());
  }
  return triangles;
}

std::vector<Triangle> triangulate(const PlanarPolygon& polygon) {
  return triangulate(polygon.outer_uv, polygon.holes_uv);
}

}  // namespace conicloc::maps
