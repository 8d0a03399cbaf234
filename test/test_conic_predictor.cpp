// ConicScanPredictor against a brute-force ray/polygon intersection written here, independently
// of the conic code: thousands of random poses and beams in a box-room map with holes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "localizer/conic/conic_scan_predictor.hpp"
#include "localizer/conic/pose.hpp"
#include "maps/planar_polygon.hpp"
#include "sensor/builtin_calibration.hpp"

namespace conicloc::localizer {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
constexpr double kPi = std::numbers::pi;

maps::PlanarPolygon polygon(const maps::Ring3& outer, const std::vector<maps::Ring3>& holes = {}) {
  maps::PlanarPolygon out;
  EXPECT_TRUE(maps::make_planar_polygon(outer, holes, out));
  return out;
}

// An axis-aligned rectangle in the plane x = c (or y, z), corners in order.
maps::Ring3 rect_x(double x, double y0, double y1, double z0, double z1) {
  return {{x, y0, z0}, {x, y1, z0}, {x, y1, z1}, {x, y0, z1}};
}
maps::Ring3 rect_y(double y, double x0, double x1, double z0, double z1) {
  return {{x0, y, z0}, {x1, y, z0}, {x1, y, z1}, {x0, y, z1}};
}
maps::Ring3 rect_z(double z, double x0, double x1, double y0, double y1) {
  return {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}};
}

// Room A [0,8]×[0,6]×[0,3] with a door and a window in its x = 8 wall opening onto room B
// [8,14]×[0,6]×[0,3], a free-standing panel with a hole inside A, and a tilted ramp.
maps::PlaneMap box_rooms() {
  maps::PlaneMap map;
  auto add = [&](const maps::Ring3& outer, const std::vector<maps::Ring3>& holes = {}) {
    map.polygons.push_back(polygon(outer, holes));
  };
  add(rect_z(0.0, 0, 14, 0, 6));  // floor of both rooms
  add(rect_z(3.0, 0, 14, 0, 6));  // ceiling
  add(rect_x(0.0, 0, 6, 0, 3));   // west wall
  add(rect_x(14.0, 0, 6, 0, 3));  // far east wall (room B)
  add(rect_y(0.0, 0, 14, 0, 3));  // south walls
  add(rect_y(6.0, 0, 14, 0, 3));  // north walls
  add(rect_x(8.0, 0, 6, 0, 3),    // partition with a door and a window
      {rect_x(8.0, 1.0, 2.0, 0.0, 2.1), rect_x(8.0, 3.0, 5.0, 1.0, 2.0)});
  add(rect_y(3.0, 2.0, 4.0, 0.5, 2.5), {rect_y(3.0, 2.5, 3.5, 1.0, 2.0)});  // panel with a hole
  add({{10, 1, 0.2}, {12, 1, 0.8}, {12, 3, 0.8}, {10, 3, 0.2}});            // ramp in room B
  return map;
}

// Even-odd point in ring, written independently of maps::ring_contains (winding by crossings
// of the horizontal half-line), plus the distance to the nearest edge.
bool in_ring(const std::vector<Vector2d>& ring, const Vector2d& p, double& edge_distance) {
  bool inside = false;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Vector2d a = ring[i], b = ring[(i + 1) % ring.size()];
    const Vector2d ab = b - a;
    const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    edge_distance = std::min(edge_distance, (a + t * ab - p).norm());
    if ((a.y() <= p.y() && b.y() > p.y()) || (b.y() <= p.y() && a.y() > p.y())) {
      const double x = a.x() + (p.y() - a.y()) / (b.y() - a.y()) * (b.x() - a.x());
      if (x > p.x()) inside = !inside;
    }
  }
  return inside;
}

struct BruteHit {
  double range = std::numeric_limits<double>::infinity();
  double nearest_edge = std::numeric_limits<double>::infinity();  // of any plane hit, metres
};

BruteHit brute_force(const maps::PlaneMap& map, const Vector3d& origin, const Vector3d& dir) {
  BruteHit hit;
  for (const auto& poly : map.polygons) {
    const double den = poly.plane.normal.dot(dir);
    if (std::abs(den) < 1e-12) continue;
    const double t = -(poly.plane.normal.dot(origin) + poly.plane.offset) / den;
    if (!(t > 0.0)) continue;
    const Vector3d q = origin + t * dir;
    const Vector2d uv((q - poly.frame.origin).dot(poly.frame.e_u),
                      (q - poly.frame.origin).dot(poly.frame.e_v));
    double edge = std::numeric_limits<double>::infinity();
    bool inside = in_ring(poly.outer_uv, uv, edge);
    for (const auto& hole : poly.holes_uv) {
      if (in_ring(hole, uv, edge)) inside = false;
    }
    hit.nearest_edge = std::min(hit.nearest_edge, edge);
    if (inside && t < hit.range) hit.range = t;
  }
  return hit;
}

TEST(ConicPredictor, AgreesWithBruteForceOnRandomPosesAndBeams) {
  const maps::PlaneMap map = box_rooms();
  const auto calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  const PredictorConfig config{.min_range_m = 0.3};
  const double max_range_m = 100.0;
  const ConicScanPredictor predictor(map, calibration, config, max_range_m);
  PredictedScan predicted;
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int compared = 0, both_hit = 0, skipped = 0;
  for (int pose_index = 0; pose_index < 1500; ++pose_index) {
    const double x = 0.3 + unit(rng) * 13.4, y = 0.3 + unit(rng) * 5.4, z = 0.2 + unit(rng) * 2.6;
    const double tilt = pose_index % 3 == 0 ? 0.0 : 0.2;
    const Pose3 T_map_sensor =
        make_pose(x, y, z, unit(rng) * 2 * kPi, tilt * (unit(rng) - 0.5), tilt * (unit(rng) - 0.5));
    predictor.predict(T_map_sensor, predicted);
    ASSERT_EQ(predicted.rings.size(), 16u);
    for (const auto& ring : predictor.rings()) {
      const PredictedRing& line = predicted.ring(ring.ring);
      for (int b = 0; b < 8; ++b) {
        const double theta = unit(rng) * 2 * kPi;
        const Vector3d origin = T_map_sensor * ring.apex();
        const Vector3d dir = T_map_sensor.linear() * ring.direction(theta);
        const BruteHit truth = brute_force(map, origin, dir);
        // Away from polygon edges only (1e-6 relative to the range).
        if (truth.nearest_edge < 1e-6 * std::max(1.0, std::min(truth.range, 100.0))) {
          ++skipped;
          continue;
        }
        double expected = truth.range;
        if (expected < config.min_range_m || expected > max_range_m) {
          expected = PredictedRing::kNoReturn;
        }
        const double got = line.range(theta);
        ++compared;
        if (std::isfinite(expected) && std::isfinite(got)) {
          ++both_hit;
          ASSERT_NEAR(got, expected, 1e-9 * expected)
              << "pose " << pose_index << " ring " << ring.ring << " theta " << theta;
        } else {
          ASSERT_EQ(std::isfinite(got), std::isfinite(expected))
              << "pose " << pose_index << " ring " << ring.ring << " theta " << theta << " got "
              << got << " expected " << expected;
        }
      }
    }
  }
  EXPECT_GT(compared, 150000);
  EXPECT_GT(both_hit, 100000);
  EXPECT_LT(skipped, compared / 100);
}

TEST(ConicPredictor, EvaluateSortedMatchesPointwiseRange) {
  const maps::PlaneMap map = box_rooms();
  const ConicScanPredictor predictor(map, sensor::builtin_calibration(sensor::SensorModel::VLP16));
  PredictedScan predicted;
  predictor.predict(make_pose(3.0, 2.0, 1.2, 0.7), predicted);
  std::vector<double> azimuths;
  for (int i = 0; i < 1800; ++i) azimuths.push_back(i * 2 * kPi / 1800);
  AzimuthSamples samples;
  samples.assign(azimuths);
  std::vector<double> fast(azimuths.size()), plain(azimuths.size());
  for (const auto& line : predicted.rings) {
    line.evaluate_sorted(samples, fast);
    line.evaluate_sorted(azimuths, plain);
    for (std::size_t i = 0; i < azimuths.size(); ++i) {
      EXPECT_EQ(fast[i], plain[i]);
      EXPECT_EQ(plain[i], line.range(azimuths[i]));
    }
  }
}

TEST(ConicPredictor, PiecesPartitionTheCircleInOrder) {
  const maps::PlaneMap map = box_rooms();
  const ConicScanPredictor predictor(map, sensor::builtin_calibration(sensor::SensorModel::VLP16));
  PredictedScan predicted;
  predictor.predict(make_pose(9.0, 4.0, 1.0, 2.0, 0.05, -0.03), predicted);
  for (const auto& line : predicted.rings) {
    ASSERT_EQ(line.boundary_rad.size(), line.piece_count() + 1);
    EXPECT_EQ(line.boundary_rad.front(), 0.0);
    EXPECT_DOUBLE_EQ(line.boundary_rad.back(), 2 * kPi);
    for (std::size_t i = 0; i < line.piece_count(); ++i) {
      EXPECT_LT(line.boundary_rad[i], line.boundary_rad[i + 1]);
      if (line.polygon[i] < 0) {
        EXPECT_EQ(line.a[i] + line.b[i] + line.c[i], 0.0);
      }
    }
  }
}

TEST(ConicPredictor, NearestSurfaceOccludesTheRoomBehind) {
  // From room A looking east (θ = 0) through the window of the x = 8 partition: ring 8 (+1°) at
  // z = 1.5 sees room B's far wall (x = 14) through the window, the partition elsewhere.
  const maps::PlaneMap map = box_rooms();
  const ConicScanPredictor predictor(map, sensor::builtin_calibration(sensor::SensorModel::VLP16));
  PredictedScan predicted;
  predictor.predict(make_pose(6.0, 4.0, 1.5, 0.0), predicted);
  const RingGeometry& ring = predictor.rings()[8];
  ASSERT_NEAR(ring.elevation_rad, 1.0 * kPi / 180, 1e-12);
  const double through_window = (14.0 - 6.0) / ring.cos_elevation;
  EXPECT_NEAR(predicted.ring(8).range(0.0), through_window, 1e-9);
  // At θ where y hits 2.5 on the partition (outside the window, y < 3): the partition wins.
  const double theta = std::atan2(2.5 - 4.0, 2.0);
  EXPECT_NEAR(predicted.ring(8).range(theta), 2.0 / (ring.cos_elevation * std::cos(theta)), 1e-9);
  EXPECT_EQ(predicted.ring(8).polygon[predicted.ring(8).piece_at(theta)], 6);
}

TEST(ConicPredictor, RangeLimitsGiveNoReturn) {
  const maps::PlaneMap map = box_rooms();
  const ConicScanPredictor near_only(map, sensor::builtin_calibration(sensor::SensorModel::VLP16),
                                     {.min_range_m = 0.3}, 2.0);
  PredictedScan predicted;
  near_only.predict(make_pose(1.0, 3.0, 1.5, 0.0), predicted);
  // West wall at 1 m (θ = π) is in range; the partition at 7 m (θ = 0) is beyond 2 m.
  EXPECT_TRUE(std::isfinite(predicted.ring(8).range(kPi)));
  EXPECT_EQ(predicted.ring(8).range(0.0), PredictedRing::kNoReturn);
  // A wall closer than min range blocks the beam and returns nothing.
  const ConicScanPredictor far_min(map, sensor::builtin_calibration(sensor::SensorModel::VLP16),
                                   {.min_range_m = 1.5}, 100.0);
  far_min.predict(make_pose(1.0, 3.0, 1.5, 0.0), predicted);
  EXPECT_EQ(predicted.ring(8).range(kPi), PredictedRing::kNoReturn);
}

// Predicting some rings only: those are the rings of the full prediction, piece for piece, with
// fewer pairs clipped; the others are one gap, as a ring that meets nothing.
TEST(ConicPredictor, TheRingsAskedForAreTheFullPredictionsRings) {
  const maps::PlaneMap map = box_rooms();
  const ConicScanPredictor predictor(map, sensor::builtin_calibration(sensor::SensorModel::VLP16));
  const std::vector<int> candidates = {0, 1, 2, 3, 4, 5, 6, 7, 8};
  const std::vector<int> some = {2, 6, 10, 14};
  PredictedScan full, part;
  for (const Pose3& pose :
       {make_pose(9.0, 4.0, 1.0, 2.0, 0.05, -0.03), make_pose(6.0, 4.0, 1.5, 0.0)}) {
    predictor.predict(pose, candidates, full);
    predictor.predict(pose, candidates, some, part);
    ASSERT_EQ(part.rings.size(), full.rings.size());
    EXPECT_LT(part.ring_polygons_clipped, full.ring_polygons_clipped);
    for (std::size_t k = 0; k < full.rings.size(); ++k) {
      SCOPED_TRACE(k);
      const PredictedRing& got = part.rings[k];
      EXPECT_EQ(got.min_inverse_range, full.rings[k].min_inverse_range);
      EXPECT_EQ(got.max_inverse_range, full.rings[k].max_inverse_range);
      if (std::find(some.begin(), some.end(), static_cast<int>(k)) != some.end()) {
        EXPECT_EQ(got.boundary_rad, full.rings[k].boundary_rad);
        EXPECT_EQ(got.a, full.rings[k].a);
        EXPECT_EQ(got.b, full.rings[k].b);
        EXPECT_EQ(got.c, full.rings[k].c);
        EXPECT_EQ(got.polygon, full.rings[k].polygon);
      } else {
        ASSERT_EQ(got.piece_count(), 1U);
        EXPECT_EQ(got.polygon[0], -1);
        EXPECT_EQ(got.range(1.0), PredictedRing::kNoReturn);
      }
    }
  }
}

}  // namespace
}  // namespace conicloc::localizer
