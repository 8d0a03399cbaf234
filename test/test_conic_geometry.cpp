// The conic sensor model's formulas (DESIGN.md "The conic sensor model"), each checked directly.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "localizer/conic/pose.hpp"
#include "localizer/conic/projective_conic.hpp"
#include "localizer/conic/ring_conic.hpp"
#include "localizer/conic/ring_geometry.hpp"
#include "sensor/builtin_calibration.hpp"

namespace conicloc::localizer {
namespace {

using Eigen::Vector3d;
constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

// Eccentricity of a conic from its matrix alone (general second-degree curve
// Ax² + Bxy + Cy² + Dx + Ey + F = 0), independent of the |n_h|/sin|φ| formula.
double eccentricity_from_matrix(const Eigen::Matrix3d& m) {
  const double A = m(0, 0), B = 2.0 * m(0, 1), C = m(1, 1);
  const double root = std::sqrt((A - C) * (A - C) + B * B);
  const double eta = m.determinant() < 0.0 ? 1.0 : -1.0;
  return std::sqrt(2.0 * root / (eta * (A + C) + root));
}

SensorPlane random_plane(std::mt19937_64& rng) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> offset(-8.0, 8.0);
  return {Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized(), offset(rng)};
}

TEST(RingGeometry, Vlp16RingsSortedWithPrecomputedTrigonometry) {
  const auto rings = ring_geometry(sensor::builtin_calibration(sensor::SensorModel::VLP16));
  ASSERT_EQ(rings.size(), 16u);
  for (std::size_t k = 0; k < rings.size(); ++k) {
    EXPECT_EQ(rings[k].ring, static_cast<int>(k));
    EXPECT_NEAR(rings[k].elevation_rad, (-15.0 + 2.0 * k) * kDeg, 1e-12);
    EXPECT_DOUBLE_EQ(rings[k].cos_elevation, std::cos(rings[k].elevation_rad));
    EXPECT_DOUBLE_EQ(rings[k].sin_elevation, std::sin(rings[k].elevation_rad));
    EXPECT_NEAR(rings[k].direction(0.3).norm(), 1.0, 1e-15);
  }
  EXPECT_NEAR(rings[0].vertical_offset_m, 0.0112, 1e-12);  // channel 0: −15°, 11.2 mm
  EXPECT_EQ(rings[0].channel, 0);
  EXPECT_EQ(rings[15].channel, 15);
}

TEST(RingConic, CoefficientsAreTheDesignFormulas) {
  const RingGeometry ring = make_ring_geometry(-7 * kDeg, 0.0051);
  const SensorPlane plane{Vector3d(0.3, -0.5, 0.8).normalized(), -2.5};
  const RingConic conic = ring_conic(ring, plane);
  const Vector3d& n = plane.normal;
  EXPECT_DOUBLE_EQ(conic.A, n.x() * std::cos(-7 * kDeg));
  EXPECT_DOUBLE_EQ(conic.B, n.y() * std::cos(-7 * kDeg));
  EXPECT_DOUBLE_EQ(conic.C, n.z() * std::sin(-7 * kDeg));
  EXPECT_DOUBLE_EQ(conic.E, -(plane.offset + n.z() * 0.0051));
}

TEST(RingConic, PredictedPointsLieOnThePlane) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> angle(0.0, 2 * kPi);
  const auto rings = ring_geometry(sensor::builtin_calibration(sensor::SensorModel::VLP16));
  int hits = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const SensorPlane plane = random_plane(rng);
    const RingGeometry& ring = rings[trial % 16];
    const RingConic conic = ring_conic(ring, plane);
    const double theta = angle(rng);
    double r = 0.0;
    if (!conic.hit(theta, r)) continue;
    ++hits;
    const Vector3d p = ring.point(theta, r);
    EXPECT_NEAR(plane.normal.dot(p) + plane.offset, 0.0, 1e-12 * std::max(1.0, r));
    EXPECT_GT(r, 0.0);
  }
  EXPECT_GT(hits, 500);
}

TEST(RingConic, MapPlaneToSensorFrame) {
  // n_s = Rᵀn, D_s = D + n·t: a map point on the plane, expressed in the sensor frame, is on it.
  const Pose3 T = make_pose(3.0, -2.0, 1.4, 0.7, 0.1, -0.05);
  const Vector3d n = Vector3d(0.2, 0.9, -0.1).normalized();
  const double D = 4.2;
  const SensorPlane s = to_sensor_plane(n, D, T.linear(), T.translation());
  const Vector3d on_plane_map = -D * n + Vector3d(0.9, -0.2, 0.0).cross(n);
  const Vector3d on_plane_sensor = T.inverse() * on_plane_map;
  EXPECT_NEAR(s.normal.dot(on_plane_sensor) + s.offset, 0.0, 1e-12);
}

TEST(RingConic, VisibleIntervalIsExactlyWhereRangeIsPositive) {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> angle(0.0, 2 * kPi);
  const auto rings = ring_geometry(sensor::builtin_calibration(sensor::SensorModel::VLP16));
  for (int trial = 0; trial < 300; ++trial) {
    const RingConic conic = ring_conic(rings[trial % 16], random_plane(rng));
    const AzimuthInterval visible = visible_interval(conic);
    for (int s = 0; s < 50; ++s) {
      const double theta = angle(rng);
      double r = 0.0;
      const bool hit = conic.hit(theta, r);
      // Position of θ inside the interval, modulo 2π.
      double offset = std::fmod(theta - visible.begin_rad, 2 * kPi);
      if (offset < 0) offset += 2 * kPi;
      const double width = visible.end_rad - visible.begin_rad;
      const bool inside = visible.full() || (!visible.empty() && offset < width);
      const double margin = std::min(offset, std::abs(width - offset));
      if (!visible.full() && !visible.empty() && margin < 1e-9) continue;  // at an asymptote
      EXPECT_EQ(hit, inside) << "trial " << trial << " θ " << theta;
    }
  }
}

TEST(RingConic, VisibleIntervalIsCentredOnAtan2BAOrOpposite) {
  const RingGeometry ring = make_ring_geometry(3 * kDeg, 0.0);
  // Wall x = 4 in front (n towards the sensor: n = (−1, 0, 0), D = 4): E = −4 < 0, centre opposite
  // atan2(B, A) = π, i.e. θ = 0.
  const RingConic front = ring_conic(ring, {Vector3d(-1, 0, 0), 4.0});
  const AzimuthInterval v = visible_interval(front);
  EXPECT_NEAR(0.5 * (v.begin_rad + v.end_rad), 0.0, 1e-15);
  EXPECT_NEAR(v.end_rad - v.begin_rad, kPi, 1e-15);  // a vertical wall: half the ring
  // Same plane with the normal flipped: E > 0, centre atan2(B, A) = 0 again.
  const RingConic flipped = ring_conic(ring, {Vector3d(1, 0, 0), -4.0});
  const AzimuthInterval w = visible_interval(flipped);
  EXPECT_NEAR(0.5 * (w.begin_rad + w.end_rad), 0.0, 1e-15);
}

TEST(ProjectiveConic, AgreesWithRayFormOnEveryPredictedPoint) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> angle(0.0, 2 * kPi);
  const auto rings = ring_geometry(sensor::builtin_calibration(sensor::SensorModel::VLP16));
  int checked = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const SensorPlane plane = random_plane(rng);
    const RingGeometry& ring = rings[trial % 16];
    const RingConic ray = ring_conic(ring, plane);
    const ProjectiveConic conic = projective_conic(ring, plane);
    if (conic.type == ConicType::Degenerate) continue;
    const Eigen::Matrix3d& H = conic.H;
    EXPECT_NEAR((H.col(0).cross(H.col(1)) - plane.normal).norm(), 0.0, 1e-12);
    for (int s = 0; s < 20; ++s) {
      const double theta = angle(rng);
      double r = 0.0;
      if (!ray.hit(theta, r) || r > 1e4) continue;
      const Vector3d p = ring.point(theta, r);
      const double u = (p - conic.foot_point).dot(conic.e_u);
      const double v = (p - conic.foot_point).dot(conic.e_v);
      EXPECT_NEAR((conic.point(u, v) - p).norm(), 0.0, 1e-9 * r);
      // Homogeneous: scale by the squared size of (u, v, 1) in metres.
      EXPECT_NEAR(conic.evaluate(u, v), 0.0, 1e-12 * (u * u + v * v + r * r + 1.0));
      ++checked;
    }
  }
  EXPECT_GT(checked, 2000);
}

TEST(ProjectiveConic, EccentricityFormulaMatchesTheMatrix) {
  std::mt19937_64 rng(4);
  const auto rings = ring_geometry(sensor::builtin_calibration(sensor::SensorModel::VLP16));
  for (int trial = 0; trial < 500; ++trial) {
    const SensorPlane plane = random_plane(rng);
    const ProjectiveConic conic = projective_conic(rings[trial % 16], plane);
    if (conic.type == ConicType::Degenerate || std::abs(conic.eccentricity - 1.0) < 1e-3) continue;
    EXPECT_NEAR(eccentricity_from_matrix(conic.C), conic.eccentricity,
                1e-7 * std::max(1.0, conic.eccentricity));
    EXPECT_EQ(conic.type, conic.eccentricity < 1 ? ConicType::Ellipse : ConicType::Hyperbola);
  }
}

TEST(ProjectiveConic, ManhattanWallsAreHyperbolasOfEccentricityOneOverSinPhiAtEveryDistance) {
  const auto rings = ring_geometry(sensor::builtin_calibration(sensor::SensorModel::VLP16));
  for (const RingGeometry& ring : rings) {
    for (const double distance : {0.5, 2.0, 7.5, 40.0}) {
      for (const Vector3d& normal : {Vector3d(1, 0, 0), Vector3d(0, -1, 0), Vector3d(-1, 0, 0)}) {
        const ProjectiveConic conic = projective_conic(ring, {normal, distance});
        EXPECT_EQ(conic.type, ConicType::Hyperbola);
        const double expected = 1.0 / std::abs(std::sin(ring.elevation_rad));
        EXPECT_NEAR(conic.eccentricity, expected, 1e-12 * expected);
        EXPECT_NEAR(eccentricity_from_matrix(conic.C), expected, 1e-9 * expected);
      }
    }
  }
}

TEST(ProjectiveConic, LevelFloorsAndCeilingsAreCirclesTiltedOnesEllipses) {
  const auto rings = ring_geometry(sensor::builtin_calibration(sensor::SensorModel::VLP16));
  for (const RingGeometry& ring : rings) {
    const bool down = ring.elevation_rad < 0.0;
    // Floor 1.5 m below (n up, D = 1.5) for downward rings, ceiling 1.5 m above for upward ones.
    const SensorPlane level =
        down ? SensorPlane{Vector3d(0, 0, 1), 1.5} : SensorPlane{Vector3d(0, 0, -1), 1.5};
    const ProjectiveConic circle = projective_conic(ring, level);
    EXPECT_EQ(circle.type, ConicType::Ellipse);
    EXPECT_EQ(circle.eccentricity, 0.0);
    EXPECT_NEAR(circle.C(0, 0), circle.C(1, 1), 1e-15);
    EXPECT_NEAR(circle.C(0, 1), 0.0, 1e-15);
    // A ring's circle on a level plane: every beam has the same range.
    const RingConic ray = ring_conic(ring, level);
    EXPECT_NEAR(ray.range(0.1), ray.range(2.9), 1e-12);
    // Tilted by less than |φ|: an ellipse.
    const double tilt = 0.5 * std::abs(ring.elevation_rad);
    const Vector3d n = down ? Vector3d(std::sin(tilt), 0, std::cos(tilt))
                            : Vector3d(std::sin(tilt), 0, -std::cos(tilt));
    const ProjectiveConic ellipse = projective_conic(ring, {n, 1.5});
    EXPECT_EQ(ellipse.type, ConicType::Ellipse);
    EXPECT_NEAR(ellipse.eccentricity, std::sin(tilt) / std::abs(std::sin(ring.elevation_rad)),
                1e-12);
    EXPECT_NEAR(eccentricity_from_matrix(ellipse.C), ellipse.eccentricity, 1e-9);
  }
}

TEST(ProjectiveConic, ConeTangentToPlaneIsAParabola) {
  // |n_h| = sin|φ|: the plane is parallel to one generator of the cone (e = 1).
  const RingGeometry ring = make_ring_geometry(-9 * kDeg, 0.0066);
  const double phi = std::abs(ring.elevation_rad);
  const SensorPlane plane{Vector3d(std::sin(phi), 0.0, std::cos(phi)), 1.2};
  const ProjectiveConic conic = projective_conic(ring, plane);
  EXPECT_EQ(conic.type, ConicType::Parabola);
  EXPECT_NEAR(conic.eccentricity, 1.0, 1e-15);
  // The parabola's 2×2 block is singular.
  const Eigen::Matrix2d block = conic.C.topLeftCorner<2, 2>();
  EXPECT_NEAR(block.determinant(), 0.0, 1e-15);
  // The ray form stays finite: only the beam along the generator (θ = 0) goes to infinity.
  const RingConic ray = ring_conic(ring, plane);
  const AzimuthInterval visible = visible_interval(ray);
  EXPECT_NEAR(visible.end_rad - visible.begin_rad, 2 * kPi, 1e-6);
  double r = 0.0;
  EXPECT_FALSE(ray.hit(0.0, r));  // denominator exactly 0: no division
  ASSERT_TRUE(ray.hit(kPi, r));
  EXPECT_TRUE(std::isfinite(r));
  ASSERT_TRUE(ray.hit(1e-3, r));
  EXPECT_GT(r, 1e5);
  EXPECT_TRUE(std::isfinite(r));
}

TEST(NumericalStability, HorizontalRingPhiZero) {
  const RingGeometry ring = make_ring_geometry(0.0, 0.0);
  const SensorPlane wall{Vector3d(-1, 0, 0), 3.0};
  const RingConic ray = ring_conic(ring, wall);
  EXPECT_EQ(ray.C, 0.0);
  EXPECT_NEAR(ray.range(0.0), 3.0, 1e-15);
  const AzimuthInterval visible = visible_interval(ray);
  EXPECT_NEAR(visible.end_rad - visible.begin_rad, kPi, 1e-15);
  const ProjectiveConic conic = projective_conic(ring, wall);
  EXPECT_EQ(conic.type, ConicType::Degenerate);  // the cone is a plane: the conic is a line
  EXPECT_TRUE(std::isinf(conic.eccentricity));
  EXPECT_TRUE(conic.C.allFinite());
  // A level plane is never hit by a horizontal ring, and nothing divides by zero.
  const RingConic floor = ring_conic(ring, {Vector3d(0, 0, 1), 1.0});
  EXPECT_TRUE(visible_interval(floor).empty());
  double r = 0.0;
  EXPECT_FALSE(floor.hit(1.0, r));
  EXPECT_EQ(conic_eccentricity(ring, Vector3d(0, 0, 1)), 0.0);
}

TEST(NumericalStability, NearlyHorizontalRingsPlusMinusOneDegree) {
  for (const double phi : {1 * kDeg, -1 * kDeg}) {
    const RingGeometry ring = make_ring_geometry(phi, 0.0007);
    const SensorPlane wall{Vector3d(0, -1, 0), 5.0};
    const ProjectiveConic conic = projective_conic(ring, wall);
    EXPECT_EQ(conic.type, ConicType::Hyperbola);
    EXPECT_NEAR(conic.eccentricity, 1.0 / std::sin(1 * kDeg), 1e-9);
    EXPECT_NEAR(eccentricity_from_matrix(conic.C), conic.eccentricity, 1e-6);
    const RingConic ray = ring_conic(ring, wall);
    EXPECT_NEAR(ray.range(kPi / 2), 5.0 / std::cos(phi), 1e-12);
    // A floor 1.7 m down is reached only by the downward ring, at 1.7/sin 1° ≈ 97 m.
    const SensorPlane floor{Vector3d(0, 0, 1), 1.7};
    double r = 0.0;
    EXPECT_EQ(ring_conic(ring, floor).hit(0.4, r), phi < 0);
    if (phi < 0) {
      EXPECT_NEAR(r, (1.7 + 0.0007) / std::sin(1 * kDeg), 1e-9);
    }
  }
}

TEST(NumericalStability, PlaneThroughTheApexHasNoPositiveRange) {
  const RingGeometry ring = make_ring_geometry(5 * kDeg, 0.0);
  const SensorPlane through{Vector3d(0.6, 0.8, 0.0), 0.0};  // D → 0: contains the apex
  const RingConic ray = ring_conic(ring, through);
  EXPECT_EQ(ray.E, 0.0);
  EXPECT_TRUE(visible_interval(ray).empty());
  double r = 1.0;
  for (int i = 0; i < 36; ++i) EXPECT_FALSE(ray.hit(i * 10 * kDeg, r));
  EXPECT_EQ(projective_conic(ring, through).type, ConicType::Degenerate);
  EXPECT_TRUE(projective_conic(ring, through).C.allFinite());
  // Almost through (D = 1e-12): the ranges are tiny and positive, still finite.
  const RingConic almost = ring_conic(ring, {Vector3d(0.6, 0.8, 0.0), 1e-12});
  EXPECT_FALSE(visible_interval(almost).empty());
  double tiny = 0.0;
  ASSERT_TRUE(almost.hit(std::atan2(-0.8, -0.6), tiny));
  EXPECT_NEAR(tiny, 1e-12 / std::cos(5 * kDeg), 1e-24);
}

TEST(NumericalStability, GrazingBeamDenominatorToZero) {
  // Wall x = 2: beams at θ → ±90° graze it; the range grows without bound, never NaN.
  const RingGeometry ring = make_ring_geometry(-1 * kDeg, 0.0);
  const RingConic ray = ring_conic(ring, {Vector3d(-1, 0, 0), 2.0});
  double r = 0.0;
  // cos(π/2) rounds to 6e-17: a hit at ~1e16 m or a miss, never NaN or a negative range.
  if (ray.hit(kPi / 2, r)) {
    EXPECT_GT(r, 1e15);
  }
  ASSERT_TRUE(ray.hit(kPi / 2 - 1e-9, r));
  EXPECT_NEAR(r, 2.0 / (std::cos(1 * kDeg) * std::sin(1e-9)), 1e3);
  EXPECT_FALSE(ray.hit(kPi / 2 + 1e-9, r));
}

}  // namespace
}  // namespace conicloc::localizer
