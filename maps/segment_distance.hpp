#pragma once
// Distance from a point to a line segment, and to a closed ring of them, in the plane.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace conicloc::maps {

/// |p − q|² for q the point of segment [a, b] closest to p: q = a + t(b − a), t = (p − a)·(b − a)
/// / |b − a|² clamped to [0, 1] (t = 0 for a degenerate segment).
inline double squared_distance_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                                          const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).squaredNorm();
}

/// Distance from p to the nearest edge of the closed ring (last vertex joined to the first);
/// infinity for an empty ring.
inline double distance_to_ring(const std::vector<Eigen::Vector2d>& ring, const Eigen::Vector2d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < ring.size(); ++i) {
    best = std::min(best, squared_distance_to_segment(p, ring[i], ring[(i + 1) % ring.size()]));
  }
  return std::sqrt(best);
}

}  // namespace conicloc::maps
