// Scan-line segmentation: conic segments by linear least squares on 1/r, and the planes they give.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "localizer/conic/ring_conic.hpp"
#include "localizer/models/scan_line_segmentation.hpp"
#include "sensor/laser_calibration.hpp"

namespace conicloc::localizer {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

// A square room 6 m × 6 m around the sensor, turned 45° so its corners lie at θ = 0, 90°, ...
std::vector<SensorPlane> diamond_room() {
  std::vector<SensorPlane> walls;
  for (int k = 0; k < 4; ++k) {
    const double angle = 45 * kDeg + k * 90 * kDeg;
    walls.push_back({Eigen::Vector3d(-std::cos(angle), -std::sin(angle), 0.0), 3.0});
  }
  return walls;
}

sensor::RingScan scan_ring(const RingGeometry& ring, const std::vector<SensorPlane>& planes,
                           double noise_m, std::mt19937_64& rng) {
  std::normal_distribution<double> noise(0.0, noise_m);
  sensor::RingScan scan;
  scan.elevation_rad = ring.elevation_rad;
  scan.vertical_offset_m = ring.vertical_offset_m;
  for (int i = 0; i < 1800; ++i) {
    const double theta = (i + 0.5) * 2 * kPi / 1800;
    double best = std::numeric_limits<double>::infinity();
    for (const auto& plane : planes) {
      double r = 0.0;
      if (ring_conic(ring, plane).hit(theta, r)) best = std::min(best, r);
    }
    sensor::Return ret;
    ret.azimuth_rad = theta;
    ret.range_m = best + (noise_m > 0 ? noise(rng) : 0.0);
    scan.returns.push_back(ret);
  }
  return scan;
}

TEST(ScanLineSegmentation, FitRecoversTheCoefficientsExactly) {
  const RingGeometry ring = make_ring_geometry(-5 * kDeg, 0.0037);
  const SensorPlane plane{Eigen::Vector3d(0.3, -0.9, 0.2).normalized(), 4.0};
  const RingConic conic = ring_conic(ring, plane);
  std::vector<double> theta, range;
  for (int i = 0; i < 40; ++i) {
    double r = 0.0;
    const double t = 1.0 + i * 0.01;
    if (conic.hit(t, r)) {
      theta.push_back(t);
      range.push_back(r);
    }
  }
  ASSERT_GE(theta.size(), 30u);
  double a = 0, b = 0, c = 0;
  ASSERT_TRUE(fit_inverse_range(theta.data(), range.data(), theta.size(), a, b, c));
  EXPECT_NEAR(a, conic.A / conic.E, 1e-9);
  EXPECT_NEAR(b, conic.B / conic.E, 1e-9);
  EXPECT_NEAR(c, conic.C / conic.E, 1e-9);
  EXPECT_FALSE(fit_inverse_range(theta.data(), range.data(), 2, a, b, c));
}

TEST(ScanLineSegmentation, DiamondRoomGivesFourWallsAndTheirPlanes) {
  std::mt19937_64 rng(5);
  const auto walls = diamond_room();
  for (const double phi : {-15 * kDeg, -3 * kDeg, 1 * kDeg, 11 * kDeg}) {
    const RingGeometry ring = make_ring_geometry(phi, 0.005);
    const auto segments =
        segment_scan_line(scan_ring(ring, walls, 0.0, rng), {}, sensor::kMaxRange_m);
    ASSERT_EQ(segments.size(), 4u) << "φ " << phi / kDeg;
    for (const ConicSegment& s : segments) {
      EXPECT_TRUE(s.tilt_observable);
      EXPECT_LT(s.rms_residual_m, 1e-9);
      // The wall this segment lies on: the one facing its middle azimuth.
      const double mid = 0.5 * (s.begin_rad + s.end_rad);
      const int k = static_cast<int>(std::floor(std::fmod(mid, 2 * kPi) / (90 * kDeg)));
      EXPECT_NEAR((s.normal_sensor - walls[k].normal).norm(), 0.0, 1e-7) << "φ " << phi / kDeg;
      EXPECT_NEAR(s.offset_sensor, walls[k].offset, 1e-7);
      EXPECT_NEAR(s.trace_distance_m, 3.0, 1e-7);
      // Corners at multiples of 90°: each segment spans one quarter, up to the sample spacing.
      EXPECT_NEAR(s.end_rad - s.begin_rad, 90 * kDeg, 0.5 * kDeg);
    }
  }
}

TEST(ScanLineSegmentation, HorizontalRingReportsTiltUnobservable) {
  std::mt19937_64 rng(6);
  const RingGeometry ring = make_ring_geometry(0.0, 0.0);
  // A wall tilted 10° from vertical: from a φ = 0 ring it looks like a vertical wall at some
  // distance; only the horizontal normal and the trace distance are reported.
  std::vector<SensorPlane> planes = diamond_room();
  planes[0].normal =
      Eigen::Vector3d(-std::cos(45 * kDeg) * std::cos(10 * kDeg),
                      -std::sin(45 * kDeg) * std::cos(10 * kDeg), std::sin(10 * kDeg));
  const auto segments =
      segment_scan_line(scan_ring(ring, planes, 0.0, rng), {}, sensor::kMaxRange_m);
  ASSERT_EQ(segments.size(), 4u);
  for (const auto& s : segments) {
    EXPECT_FALSE(s.tilt_observable);
    EXPECT_TRUE(s.normal_sensor.isZero());
    EXPECT_TRUE(std::isfinite(s.trace_distance_m));
    EXPECT_NEAR(std::abs(s.c), 0.0, 1e-9);
  }
  // The tilted wall's trace at z = 0 lies 3 / cos 10° from the axis, facing 45° + 180°.
  int tilted = 0;
  for (const auto& s : segments) {
    if (std::abs(s.trace_distance_m - 3.0) < 1e-7) continue;
    ++tilted;
    EXPECT_NEAR(s.trace_distance_m, 3.0 / std::cos(10 * kDeg), 1e-7);
    EXPECT_NEAR(s.horizontal_normal.x(), -std::cos(45 * kDeg), 1e-9);
    EXPECT_NEAR(s.horizontal_normal.y(), -std::sin(45 * kDeg), 1e-9);
  }
  EXPECT_EQ(tilted, 1);
}

TEST(ScanLineSegmentation, NoisyRingStillSplitsAtCornersAndGaps) {
  std::mt19937_64 rng(7);
  const RingGeometry ring = make_ring_geometry(-7 * kDeg, 0.0051);
  sensor::RingScan scan = scan_ring(ring, diamond_room(), 0.01, rng);
  // A dropout of 10° in the second wall: it splits there.
  for (auto& ret : scan.returns) {
    if (ret.azimuth_rad > 130 * kDeg && ret.azimuth_rad < 140 * kDeg) {
      ret.status = sensor::ReturnStatus::NoReturn;
    }
  }
  const auto segments = segment_scan_line(scan, {}, sensor::kMaxRange_m);
  ASSERT_EQ(segments.size(), 5u);
  for (const auto& s : segments) {
    EXPECT_LT(s.rms_residual_m, 0.02);
    ASSERT_TRUE(s.tilt_observable);
    EXPECT_LT(std::abs(s.normal_sensor.z()), 0.1);  // walls stay near vertical under 1 cm noise
  }
}

TEST(InverseRangeSums, WindowResidualIsTheDirectFitsLateInALongRunWithFarReturns) {
  // One turn of 1800 returns in a 6 m square room, 3 cm noise, with every 7th of the first 1500
  // returns from 60 m away (far returns make the running sums large); every short window of the
  // last 300 samples (walls only) and some long ones, against the residual of its own
  // least-squares fit. The normal equations square the fit's condition number, so they agree
  // to rounding times that: within 1e-7 of the window's Σ r² where it is summed directly, within
  // 1e-8 of the run's Σ r² up to its end where running sums are subtracted (measured: 1.0e-8
  // and 5.6e-10).
  std::mt19937_64 rng(2);
  std::normal_distribution<double> noise(0.0, 0.03);
  std::vector<double> cos_theta, sin_theta, range;
  for (int i = 0; i < 1800; ++i) {
    const double theta = 2.0 * kPi * i / 1800;
    const double wall = 3.0 / std::max(std::abs(std::cos(theta)), std::abs(std::sin(theta)));
    cos_theta.push_back(std::cos(theta));
    sin_theta.push_back(std::sin(theta));
    range.push_back((i < 1500 && i % 7 == 0 ? 60.0 : wall) + noise(rng));
  }
  InverseRangeSums sums;
  sums.build(cos_theta, sin_theta, range);
  int compared = 0;
  for (std::size_t first = 1500; first + 3 <= range.size(); ++first) {
    for (const std::size_t n : {3u, 4u, 5u, 6u, 8u, 11u, 15u, 16u, 17u, 40u, 200u}) {
      const std::size_t end = std::min(first + n, range.size());
      if (end - first < 3) continue;
      double a = 0, b = 0, c = 0;
      if (!fit_inverse_range_trig(&cos_theta[first], &sin_theta[first], &range[first], end - first,
                                  a, b, c)) {
        continue;
      }
      double direct = 0.0;
      for (std::size_t i = first; i < end; ++i) {
        const double r2 = range[i] * range[i];
        const double residual = r2 * (a * cos_theta[i] + b * sin_theta[i] + c) - range[i];
        direct += residual * residual;
      }
      const double sse = sums.sse(first, end);
      ASSERT_TRUE(std::isfinite(sse)) << "window " << first << " + " << end - first;
      double window_scale = 0.0, run_scale = 0.0;
      for (std::size_t i = 0; i < end; ++i) {
        run_scale += range[i] * range[i];
        window_scale += i >= first ? range[i] * range[i] : 0.0;
      }
      const double tolerance =
          end - first < InverseRangeSums::kDirectWindow ? 1e-7 * window_scale : 1e-8 * run_scale;
      EXPECT_NEAR(sse, direct, tolerance) << "window " << first << " + " << end - first;
      ++compared;
    }
  }
  EXPECT_GT(compared, 3000);
}

}  // namespace
}  // namespace conicloc::localizer
