#pragma once
// Distance from a point to a line segment in the plane.

#include <Eigen/Core>
#include <algorithm>

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

}  // namespace conicloc::maps
