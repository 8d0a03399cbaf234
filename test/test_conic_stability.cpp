// Numerical stability of the conic predictor (DESIGN.md "Numerical stability"), each case named.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "localizer/conic/conic_scan_predictor.hpp"
#include "localizer/conic/plane_culling.hpp"
#include "localizer/conic/ring_geometry.hpp"
#include "maps/plane_index.hpp"
#include "sensor/builtin_calibration.hpp"

namespace conicloc::localizer {
namespace {

using Eigen::Vector3d;
constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

void add(maps::PlaneMap& map, const maps::Ring3& outer,
         const std::vector<maps::Ring3>& holes = {}) {
  maps::PlanarPolygon polygon;
  ASSERT_TRUE(maps::make_planar_polygon(outer, holes, polygon));
  map.polygons.push_back(polygon);
}

// A 10 × 8 × 3 m room whose corner is at `corner`.
maps::PlaneMap room_at(const Vector3d& corner) {
  maps::PlaneMap map;
  const double x0 = corner.x(), y0 = corner.y(), z0 = corner.z();
  const double x1 = x0 + 10, y1 = y0 + 8, z1 = z0 + 3;
  add(map, {{x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0}});
  add(map, {{x0, y0, z1}, {x0, y1, z1}, {x1, y1, z1}, {x1, y0, z1}});
  add(map, {{x0, y0, z0}, {x0, y0, z1}, {x1, y0, z1}, {x1, y0, z0}});
  add(map, {{x1, y0, z0}, {x1, y0, z1}, {x1, y1, z1}, {x1, y1, z0}});
  add(map, {{x1, y1, z0}, {x1, y1, z1}, {x0, y1, z1}, {x0, y1, z0}});
  add(map, {{x0, y1, z0}, {x0, y1, z1}, {x0, y0, z1}, {x0, y0, z0}});
  return map;
}

sensor::LaserCalibration single_ring(double elevation_rad) {
  sensor::LaserCalibration calibration;
  calibration.lasers.push_back({elevation_rad, 0.0, 0.0, 0});
  return calibration;
}

TEST(NumericalStability, GeoreferencedCoordinatesThroughTheMapOrigin) {
  // The same room at 10⁶–10⁷ m (UTM-like) and near zero: predicted ranges agree to 1e-9 relative
  // when poses and planes are both expressed in the shifted map frame, and stay within 1e-6 m
  // even without the shift (double precision at 10⁷ m).
  const Vector3d offset(6.5e5, 5.4e6, 0.0);
  const maps::PlaneMap near_zero = room_at(Vector3d::Zero());
  const maps::PlaneMap far_away = room_at(offset);
  const auto calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  const ConicScanPredictor near_predictor(near_zero, calibration);
  const ConicScanPredictor far_predictor(far_away, calibration);
  PredictedScan near_scan, far_scan;
  near_predictor.predict(make_pose(3.3, 4.1, 1.2, 0.4), near_scan);
  far_predictor.predict(make_pose(offset.x() + 3.3, offset.y() + 4.1, 1.2, 0.4), far_scan);
  int compared = 0;
  for (int k = 0; k < 16; ++k) {
    for (int i = 0; i < 360; ++i) {
      const double theta = (i + 0.37) * kDeg;
      const double a = near_scan.ring(k).range(theta), b = far_scan.ring(k).range(theta);
      ASSERT_EQ(std::isfinite(a), std::isfinite(b));
      if (!std::isfinite(a)) continue;
      EXPECT_NEAR(a, b, 1e-6);
      ++compared;
    }
  }
  EXPECT_EQ(compared, 16 * 360);
}

TEST(NumericalStability, HorizontalAndNearlyHorizontalRingsInARoom) {
  const maps::PlaneMap map = room_at(Vector3d::Zero());
  for (const double phi : {0.0, 1 * kDeg, -1 * kDeg}) {
    const ConicScanPredictor predictor(map, single_ring(phi));
    PredictedScan scan;
    predictor.predict(make_pose(5.0, 4.0, 1.5, 0.0), scan);
    // East wall x = 10 at θ = 0: range 5 / cos φ; a horizontal ring never sees floor or ceiling.
    EXPECT_NEAR(scan.ring(0).range(0.0), 5.0 / std::cos(phi), 1e-12);
    for (std::size_t i = 0; i < scan.ring(0).piece_count(); ++i) {
      EXPECT_TRUE(std::isfinite(scan.ring(0).a[i] + scan.ring(0).b[i] + scan.ring(0).c[i]));
      if (phi == 0.0) {
        EXPECT_GT(scan.ring(0).polygon[i], 1);  // neither floor (0) nor ceiling (1)
      }
    }
  }
}

TEST(NumericalStability, SensorOnAWallPlaneAndGrazingBeams) {
  // The sensor stands exactly in the plane y = 0 of the south wall (D_s = 0) and 1e-12 m off it.
  const maps::PlaneMap map = room_at(Vector3d::Zero());
  const auto calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  const ConicScanPredictor predictor(map, calibration);
  PredictedScan scan;
  for (const double y : {0.0, 1e-12, -1e-12}) {
    predictor.predict(make_pose(5.0, y, 1.5, 0.3), scan);
    for (const auto& ring : scan.rings) {
      for (int i = 0; i < 720; ++i) {
        const double r = ring.range(i * 0.5 * kDeg);
        EXPECT_TRUE(std::isinf(r) || (r > 0.0 && std::isfinite(r)));
      }
      for (std::size_t i = 0; i < ring.piece_count(); ++i) {
        EXPECT_TRUE(std::isfinite(ring.a[i]) && std::isfinite(ring.b[i]) &&
                    std::isfinite(ring.c[i]));
      }
    }
    // Looking north (θ = 90° − yaw): from on or inside the wall plane the north wall y = 8 is
    // hit; from 1e-12 m behind it the south wall blocks the beam at ~1e-12 m, under the minimum
    // range: no return.
    const RingGeometry& ring = predictor.rings()[8];
    if (y >= 0.0) {
      EXPECT_NEAR(scan.ring(8).range(kPi / 2 - 0.3), (8.0 - y) / ring.cos_elevation, 1e-9) << y;
    } else {
      EXPECT_EQ(scan.ring(8).range(kPi / 2 - 0.3), PredictedRing::kNoReturn);
    }
  }
}

TEST(NumericalStability, TinyAndSliverPolygons) {
  maps::PlaneMap map = room_at(Vector3d::Zero());
  // A 1 mm square and a 1 mm × 2 m sliver on the east wall's plane, 1 cm in front of it.
  add(map, {{9.99, 4.0, 1.5}, {9.99, 4.001, 1.5}, {9.99, 4.001, 1.501}, {9.99, 4.0, 1.501}});
  add(map, {{9.99, 2.0, 1.2}, {9.99, 2.0, 1.201}, {9.99, 0.0, 1.201}, {9.99, 0.0, 1.2}});
  const ConicScanPredictor predictor(map, single_ring(0.0));
  PredictedScan scan;
  predictor.predict(make_pose(5.0, 4.0005, 1.5005, 0.0), scan);
  // θ = 0 hits the tiny square (4.99 m), 1 mrad beside it the wall (5 m / cos).
  EXPECT_NEAR(scan.ring(0).range(0.0), 4.99, 1e-12);
  EXPECT_NEAR(scan.ring(0).range(1e-3), 5.0 / std::cos(1e-3), 1e-9);
  // The sliver sits 0.3 mm below the ring's plane at z = 1.5005: a φ = 0 ring misses it...
  EXPECT_NEAR(scan.ring(0).range(std::atan2(-3.0, 4.99)), std::hypot(5.0, 3.0 * 5.0 / 4.99), 1e-9);
  // ... and a ring through it (sensor at z = 1.2005) sees it over y ∈ (0, 2).
  predictor.predict(make_pose(5.0, 4.0, 1.2005, 0.0), scan);
  EXPECT_NEAR(scan.ring(0).range(std::atan2(-3.0, 4.99)), std::hypot(4.99, 3.0), 1e-9);
}

TEST(NumericalStability, NearlyCoplanarNeighbours) {
  // Two panels 1e-9 m apart and tilted by 1e-9 rad against each other, overlapping: the nearer
  // one wins, the range is continuous within 1e-8 m across the switch, pieces stay few.
  maps::PlaneMap map;
  add(map, {{4.0, -3, 0}, {4.0, 3, 0}, {4.0, 3, 3}, {4.0, -3, 3}});
  add(map, {{4.0 - 1e-9, -1, 0}, {4.0 + 1e-9, 5, 0}, {4.0 + 1e-9, 5, 3}, {4.0 - 1e-9, -1, 3}});
  const ConicScanPredictor predictor(map, single_ring(2 * kDeg));
  PredictedScan scan;
  predictor.predict(make_pose(0.0, 0.0, 1.5, 0.0), scan);
  const PredictedRing& line = scan.ring(0);
  EXPECT_LE(line.piece_count(), 8u);
  for (int i = -300; i <= 300; ++i) {
    const double theta = std::atan2(i * 0.01, 4.0);
    const double expected = std::hypot(4.0, i * 0.01) / std::cos(2 * kDeg);
    const double got = line.range(theta < 0 ? theta + 2 * kPi : theta);
    if (i * 0.01 > -2.999 && i * 0.01 < 2.999) {
      EXPECT_NEAR(got, expected, 1e-8) << i;
    }
  }
}

TEST(PlaneCulling, CountsAndKeepsWhatCanBeSeen) {
  maps::PlaneMap map = room_at(Vector3d::Zero());
  const std::size_t room = map.polygons.size();
  // A polygon 200 m away, one high above (out of the ±15° cones), one behind the west wall facing
  // away from the room (normal −x, the sensor is behind it).
  add(map, {{200, 0, 0}, {201, 0, 0}, {201, 0, 3}, {200, 0, 3}});
  add(map, {{4, 3, 30}, {4, 5, 30}, {6, 5, 30}, {6, 3, 30}});
  add(map, {{-1, 0, 0}, {-1, 0, 3}, {-1, 8, 3}, {-1, 8, 0}});
  const auto calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  const maps::PlaneIndex index(map);
  const PlaneCuller culler(map, index, calibration, {}, 100.0);
  const CullResult result = culler.cull(make_pose(5.0, 4.0, 1.5, 0.0));
  EXPECT_EQ(result.considered, map.polygons.size());
  EXPECT_EQ(result.out_of_range, 1u);
  EXPECT_EQ(result.outside_field_of_view, 1u);
  EXPECT_EQ(result.facing_away, 1u);
  EXPECT_EQ(result.kept.size(), room);
  EXPECT_EQ(
      result.kept.size() + result.out_of_range + result.outside_field_of_view + result.facing_away,
      result.considered);
  // A region covering the whole room keeps the same; two-sided polygons are never back-culled.
  map.polygons.back().two_sided = true;
  const CullResult region = culler.cull(Eigen::AlignedBox3d(Vector3d(1, 1, 1), Vector3d(9, 7, 2)));
  EXPECT_EQ(region.facing_away, 0u);
  EXPECT_EQ(region.kept.size(), room + 1);
  // The culled prediction equals the full one.
  const ConicScanPredictor predictor(map, calibration);
  PredictedScan culled_scan, full_scan;
  predictor.predict(make_pose(5.0, 4.0, 1.5, 0.0), result.kept, culled_scan);
  predictor.predict(make_pose(5.0, 4.0, 1.5, 0.0), full_scan);
  for (int k = 0; k < 16; ++k) {
    for (int i = 0; i < 360; ++i) {
      EXPECT_EQ(culled_scan.ring(k).range(i * kDeg), full_scan.ring(k).range(i * kDeg));
    }
  }
}

TEST(HomogenisedScan, RingsBecomeConcentricCirclesOfRadiusCotPhi) {
  // Points generated from the VLP-16 ring geometry in a box room (apex offsets removed, as the
  // paper's homogenisation assumes a single centre): (x/z, y/z) lies on a circle of radius
  // cot|φ|; the 16 rings give 8 distinct circles (±φ pairs share one).
  const maps::PlaneMap map = room_at(Vector3d::Zero());
  const auto calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  const ConicScanPredictor predictor(map, calibration);
  PredictedScan scan;
  predictor.predict(make_pose(5.0, 4.0, 1.5, 0.2), scan);
  std::vector<double> radii;
  for (const auto& ring : predictor.rings()) {
    for (int i = 0; i < 360; ++i) {
      const double theta = (i + 0.5) * kDeg;
      const double r = scan.ring(ring.ring).range(theta);
      ASSERT_TRUE(std::isfinite(r));
      const Vector3d p = ring.point(theta, r) - ring.apex();
      const double radius = std::hypot(p.x() / p.z(), p.y() / p.z());
      EXPECT_NEAR(radius, 1.0 / std::tan(std::abs(ring.elevation_rad)), 1e-9);
    }
    radii.push_back(std::round(1e6 / std::tan(std::abs(ring.elevation_rad))));
  }
  std::sort(radii.begin(), radii.end());
  EXPECT_EQ(std::unique(radii.begin(), radii.end()) - radii.begin(), 8);
}

}  // namespace
}  // namespace conicloc::localizer
