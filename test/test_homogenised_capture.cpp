// The paper's homogenisation claim (issue 4) on a real VLP-16 capture decoded through io/: the
// points of ring k, taken relative to the ring's apex (0, 0, o_k) (DESIGN.md "Frames") and
// homogenised as (x/z, y/z), lie on a circle of radius cot|φ_k| about the origin; the 16 rings
// give 8 concentric circles, the ±φ rings sharing one.
//
// Tolerance, from how the data is represented and computed: io/'s decoder works in float
// (relative rounding ε = 2⁻²⁴ per operation). With the range r shared by x, y and z (its own
// rounding cancels in the ratio), to first order:
//   |(x, y)| = r·cos φ·|(cos θ, sin θ)| — cos φ rounded (ε), two products (2ε), and the unit
//     vector composed from two rounded rotation tables by two products and a sum (4ε): 7ε;
//   z = r·sin φ + o_k — sin φ rounded (ε), the product (ε), o_k rounded (ε·|o_k|) and the sum
//     (ε·|z|), relative to z' = z − o_k: 2ε + ε·(|o_k| + |z|)/|z'|.
// So each point may deviate from cot|φ_k| by ε·(9 + (|z| + |o_k|)/|z'|) relative (× 1.01 for
// second-order terms and the test's double arithmetic). The bound widens only where z' is small
// against z (short returns of the low rings, whose apex offset is comparable with r·sin φ); the
// capture's worst point is about 5ε off.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <vector>

#include "io/pcap_reader.hpp"
#include "io/velodyne_stream.hpp"
#include "sensor/builtin_calibration.hpp"

namespace conicloc::io {
namespace {

const std::string kCapture =
    std::string(CONICLOC_SHARED_DATA) + "/velodyne/vlp-16-test-90deg-1-50-frames.pcap";
constexpr double kFloatEpsilon = 5.9604644775390625e-08;  // 2^-24: half an ulp, relative

// VLP-16 user manual (and VeloView): elevation of firing channel c, −15, 1, −13, 3, … , −1, 15°.
// Written out here, independent of sensor/, so a wrong channel → elevation mapping shows.
double manual_elevation_deg(int channel) {
  return channel % 2 == 0 ? -15.0 + channel : static_cast<double>(channel);
}

struct RingCircle {
  std::size_t points = 0;
  std::size_t outside_bound = 0;
  double max_relative_error = 0.0;
  double sum_radius = 0.0;
  std::size_t naive_outside_bound = 0;  ///< (x/z, y/z) without removing the apex offset
};

TEST(HomogenisedCapture, RingsOfARealVlp16ScanAreConcentricCirclesOfRadiusCotPhi) {
  if (!std::filesystem::exists(kCapture)) {
    GTEST_SKIP() << "shared Velodyne data absent: " << kCapture;
  }
  const auto calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  PcapReader reader(kCapture, {velodyne::kDataPort, velodyne::kPositionPort});
  VelodyneStream stream(reader, calibration);
  std::vector<DecodedPoint> points;
  std::map<int, RingCircle> circles;  // by channel
  while (stream.next(points)) {
    for (const DecodedPoint& p : points) {
      if (!(p.range_m > 0.0f)) continue;  // no return: no point to homogenise
      const auto& laser = calibration.lasers.at(p.channel);
      const double phi = manual_elevation_deg(p.channel) * M_PI / 180.0;
      const double expected = 1.0 / std::tan(std::abs(phi));
      const double x = p.x_m, y = p.y_m, z = p.z_m;
      const double z_apex = z - laser.vertical_offset_m;  // relative to the ring's apex
      ASSERT_NE(z_apex, 0.0);
      const double radius = std::hypot(x / z_apex, y / z_apex);
      const double bound =
          1.01 * kFloatEpsilon *
          (9.0 + (std::abs(z) + std::abs(laser.vertical_offset_m)) / std::abs(z_apex));
      const double relative_error = std::abs(radius - expected) / expected;
      RingCircle& circle = circles[p.channel];
      ++circle.points;
      circle.sum_radius += radius;
      circle.max_relative_error = std::max(circle.max_relative_error, relative_error);
      circle.outside_bound += relative_error > bound ? 1 : 0;
      const double naive = std::hypot(x / z, y / z);
      circle.naive_outside_bound += std::abs(naive - expected) / expected > bound ? 1 : 0;
    }
  }
  EXPECT_EQ(stream.stats().rejected_total(), 0u);
  ASSERT_EQ(circles.size(), 16u);
  std::set<long> distinct_radii;  // in units of 1e-5 relative: far above the float error
  std::size_t naive_outside = 0;
  for (const auto& [channel, circle] : circles) {
    // 50 frames at ~1800 firings each, minus the 4 % zero distances.
    EXPECT_GT(circle.points, 20000u) << "channel " << channel;
    EXPECT_EQ(circle.outside_bound, 0u)
        << "channel " << channel << ": max relative error " << circle.max_relative_error;
    const double mean_radius = circle.sum_radius / static_cast<double>(circle.points);
    distinct_radii.insert(std::lround(std::log(mean_radius) * 1e5));
    naive_outside += circle.naive_outside_bound;
    // The −φ ring (channel 15 − c in the manual's interleaved order) lies on the same circle: the
    // two mean radii differ by no more than their points' errors from cot|φ|.
    const int mirror = 15 - channel;
    ASSERT_EQ(manual_elevation_deg(mirror), -manual_elevation_deg(channel));
    const RingCircle& partner = circles.at(mirror);
    const double partner_radius = partner.sum_radius / static_cast<double>(partner.points);
    EXPECT_LE(std::abs(mean_radius - partner_radius) / mean_radius,
              circle.max_relative_error + partner.max_relative_error + 1e-12)
        << "channels " << channel << " and " << mirror;
  }
  EXPECT_EQ(distinct_radii.size(), 8u);
  // The apex offsets are in the decoded points (DESIGN.md: p = (0, 0, o_k) + r·d_k): without
  // removing them the short returns of the offset rings leave the circle.
  EXPECT_GT(naive_outside, 1000u);
}

}  // namespace
}  // namespace conicloc::io
