#include "sim/smooth_path.hpp"

#include <algorithm>
#include <cmath>

namespace conicloc::sim {
namespace {

// Point at u ∈ [t1, t2] of the Catmull-Rom segment P1→P2 with knots t0..t3 (Barry-Goldman's
// pyramidal form of the cubic).
Eigen::Vector3d catmull_rom(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                            const Eigen::Vector3d& p2, const Eigen::Vector3d& p3, double t0,
                            double t1, double t2, double t3, double u) {
  auto lerp = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b, double ta, double tb,
                 double t) -> Eigen::Vector3d {
    return tb - ta > 1e-12 ? Eigen::Vector3d(((tb - t) * a + (t - ta) * b) / (tb - ta)) : a;
  };
  const Eigen::Vector3d a1 = lerp(p0, p1, t0, t1, u);
  const Eigen::Vector3d a2 = lerp(p1, p2, t1, t2, u);
  const Eigen::Vector3d a3 = lerp(p2, p3, t2, t3, u);
  const Eigen::Vector3d b1 = lerp(a1, a2, t0, t2, u);
  const Eigen::Vector3d b2 = lerp(a2, a3, t1, t3, u);
  return lerp(b1, b2, t1, t2, u);
}

}  // namespace

std::vector<PathSample> smooth_path(const std::vector<Eigen::Vector3d>& waypoints_in,
                                    double step_m) {
  std::vector<Eigen::Vector3d> points;
  for (const auto& p : waypoints_in) {
    if (points.empty() || (p - points.back()).norm() > 1e-6) points.push_back(p);
  }
  std::vector<PathSample> samples;
  if (points.empty()) return samples;
  std::vector<Eigen::Vector3d> dense{points.front()};
  if (points.size() >= 2) {
    // Phantom end points continue the first and last segments straight.
    std::vector<Eigen::Vector3d> padded;
    padded.push_back(2.0 * points[0] - points[1]);
    padded.insert(padded.end(), points.begin(), points.end());
    padded.push_back(2.0 * points.back() - points[points.size() - 2]);
    for (std::size_t i = 1; i + 2 < padded.size(); ++i) {
      const auto& p0 = padded[i - 1];
      const auto& p1 = padded[i];
      const auto& p2 = padded[i + 1];
      const auto& p3 = padded[i + 2];
      const double t0 = 0.0;
      const double t1 = t0 + std::sqrt((p1 - p0).norm());
      const double t2 = t1 + std::sqrt((p2 - p1).norm());
      const double t3 = t2 + std::sqrt((p3 - p2).norm());
      // Sub-steps: the chord over step_m, times 2 for the curve being longer than the chord.
      const int steps = std::max(2, static_cast<int>(std::ceil(2.0 * (p2 - p1).norm() / step_m)));
      for (int k = 1; k <= steps; ++k) {
        const double u = t1 + (t2 - t1) * k / steps;
        dense.push_back(catmull_rom(p0, p1, p2, p3, t0, t1, t2, t3, u));
      }
    }
  }
  samples.resize(dense.size());
  for (std::size_t i = 0; i < dense.size(); ++i) {
    samples[i].position = dense[i];
    if (i > 0) samples[i].s_m = samples[i - 1].s_m + (dense[i] - dense[i - 1]).norm();
  }
  // Heading from the horizontal chord around each sample; a vertical move keeps the last heading.
  for (std::size_t i = 0; i < dense.size(); ++i) {
    const std::size_t a = i == 0 ? 0 : i - 1;
    const std::size_t b = std::min(i + 1, dense.size() - 1);
    const Eigen::Vector2d chord = (dense[b] - dense[a]).head<2>();
    samples[i].heading_rad = chord.norm() > 1e-9 ? std::atan2(chord.y(), chord.x())
                                                 : (i > 0 ? samples[i - 1].heading_rad : 0.0);
  }
  for (std::size_t i = 1; i + 1 < dense.size(); ++i) {
    double turn = samples[i + 1].heading_rad - samples[i - 1].heading_rad;
    turn = std::remainder(turn, 2.0 * M_PI);
    const double ds = samples[i + 1].s_m - samples[i - 1].s_m;
    samples[i].curvature = ds > 1e-9 ? turn / ds : 0.0;
  }
  return samples;
}

}  // namespace conicloc::sim
