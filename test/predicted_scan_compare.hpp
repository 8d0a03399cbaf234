#pragma once
// Two predicted scans agree: at 720 azimuths per ring, the same surface and the same range (both
// no-return, or within `relative` of each other), skipping azimuths within 1e-9 rad of a piece
// boundary of either scan. The same surface: the same polygon, or (given the map) two polygons
// on one plane, which tie in range wherever both are seen, so rounding picks either; where both
// predict no return and one names a surface beyond the sensor's range, any (or none).

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "localizer/conic/conic_scan_predictor.hpp"
#include "localizer/conic/predicted_scan.hpp"
#include "maps/plane_map.hpp"

namespace conicloc::test {

/// Returns the number of azimuths compared.
inline int expect_same_scans(const localizer::PredictedScan& a, const localizer::PredictedScan& b,
                             double relative, const std::string& where,
                             const maps::PlaneMap* map = nullptr) {
  const auto same_surface = [map](int p, int q) {
    if (p == q) return true;
    if (map == nullptr || p < 0 || q < 0) return false;
    const maps::Plane& x = map->polygons[static_cast<std::size_t>(p)].plane;
    const maps::Plane& y = map->polygons[static_cast<std::size_t>(q)].plane;
    const double sign = x.normal.dot(y.normal) < 0.0 ? -1.0 : 1.0;
    return (x.normal - sign * y.normal).norm() < 1e-9 &&
           std::abs(x.offset - sign * y.offset) < 1e-9;
  };
  int compared = 0;
  EXPECT_EQ(a.rings.size(), b.rings.size()) << where;
  for (std::size_t k = 0; k < a.rings.size() && k < b.rings.size(); ++k) {
    const auto near_boundary = [](const localizer::PredictedRing& ring, double theta) {
      const std::size_t i = ring.piece_at(theta);
      return theta - ring.boundary_rad[i] < 1e-9 || ring.boundary_rad[i + 1] - theta < 1e-9;
    };
    const localizer::PredictedRing &ring_a = a.rings[k], &ring_b = b.rings[k];
    for (int i = 0; i < 720; ++i) {
      const double theta = 2.0 * std::numbers::pi * (i + 0.37) / 720;
      if (near_boundary(ring_a, theta) || near_boundary(ring_b, theta)) continue;
      const std::size_t piece_a = ring_a.piece_at(theta), piece_b = ring_b.piece_at(theta);
      const int polygon_a = ring_a.polygon[piece_a], polygon_b = ring_b.polygon[piece_b];
      const double ra = ring_a.range(theta), rb = ring_b.range(theta);
      // Beyond the sensor's range nothing is seen: a predictor may leave such a surface out.
      const auto beyond_range = [theta](const localizer::PredictedRing& ring, std::size_t piece) {
        return ring.polygon[piece] >= 0 &&
               ring.a[piece] * std::cos(theta) + ring.b[piece] * std::sin(theta) + ring.c[piece] <=
                   ring.min_inverse_range;
      };
      const bool unseen = std::isinf(ra) && std::isinf(rb) &&
                          (beyond_range(ring_a, piece_a) || beyond_range(ring_b, piece_b));
      EXPECT_TRUE(unseen || same_surface(polygon_a, polygon_b))
          << where << " ring " << k << " azimuth " << theta << ": polygon " << polygon_a
          << " against " << polygon_b;
      if (std::isinf(ra) || std::isinf(rb)) {
        EXPECT_EQ(ra, rb) << where << " ring " << k << " azimuth " << theta;
      } else {
        EXPECT_NEAR(ra, rb, relative * ra) << where << " ring " << k << " azimuth " << theta;
      }
      ++compared;
    }
  }
  return compared;
}

/// Two predictors of one map (different shortcuts) predict the same scans from `poses` random poses
/// in the map's bounds (yaw anywhere, roll and pitch within ±0.05 rad); with `coplanar_ok`, two
/// polygons on one plane count as the same surface (for a shortcut that changes the order in
/// which tied arcs meet). Returns the number of azimuths compared.
inline int expect_same_predictions(const localizer::ConicScanPredictor& a,
                                   const localizer::ConicScanPredictor& b, double relative,
                                   unsigned seed, int poses = 40, bool coplanar_ok = false) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::AlignedBox3d& box = a.map().bounds;
  localizer::PredictedScan scan_a, scan_b;
  int compared = 0;
  for (int pose = 0; pose < poses; ++pose) {
    const Eigen::Vector3d p =
        box.min() +
        (box.max() - box.min()).cwiseProduct(Eigen::Vector3d(unit(rng), unit(rng), unit(rng)));
    const localizer::Pose3 T = localizer::make_pose(p.x(), p.y(), p.z(), 6.3 * unit(rng),
                                                    0.1 * unit(rng) - 0.05, 0.1 * unit(rng) - 0.05);
    a.predict(T, scan_a);
    b.predict(T, scan_b);
    compared += expect_same_scans(scan_a, scan_b, relative, "pose " + std::to_string(pose),
                                  coplanar_ok ? &a.map() : nullptr);
  }
  return compared;
}

}  // namespace conicloc::test
