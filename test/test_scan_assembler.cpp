// Scans: one per rotation cut at a chosen azimuth, rings sorted by azimuth, partial first/last
// rotations flagged, no-returns and out-of-range returns kept with their status.
#include <gtest/gtest.h>

#include <cmath>

#include "io/packet_encoder.hpp"
#include "io/scan_assembler.hpp"
#include "io/velodyne_decoder.hpp"
#include "sensor/builtin_calibration.hpp"

namespace conicloc::io {
namespace {

const auto kCalibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
constexpr double kOmega = 2 * M_PI * 10.0;  // 600 rpm
constexpr double kSequenceS = 55.296e-6;

// Decoded points of `sequences` firing sequences starting at θ = start_rad, spinning clockwise.
std::vector<DecodedPoint> spin(int sequences, double start_rad, double t0 = 0.0) {
  PacketEncoder encoder;
  for (int i = 0; i < sequences; ++i) {
    FiringSequence s;
    s.time_s = t0 + i * kSequenceS;
    s.azimuth_rad = start_rad - kOmega * i * kSequenceS;
    for (int k = 0; k < 16; ++k) {
      s.range_m[k] = k == 3 ? 0.0 : (k == 4 ? 120.0 : 10.0);  // no return; beyond max range
      s.intensity[k] = 10;
    }
    encoder.add(s);
  }
  const VelodyneDecoder decoder(kCalibration);
  std::vector<DecodedPoint> points;
  for (const auto& packet : encoder.take_packets()) {
    EXPECT_EQ(decoder.check(packet.payload), PacketCheck::Ok);
    decoder.decode(packet.payload, packet.time_s, points);
  }
  return points;
}

TEST(ScanAssembler, OneScanPerRotationWithPartialEndsFlagged) {
  const int per_turn = static_cast<int>(std::round(0.1 / kSequenceS));  // 1808.6 sequences
  const auto points = spin(24 * 200, 1.0);  // starts mid-turn, 2.65 turns
  ScanAssemblerConfig config;
  config.max_range_m = 100.0;
  ScanAssembler assembler(kCalibration, config);
  std::vector<sensor::Scan> scans;
  assembler.add(points, scans);
  const auto last = assembler.finish();
  ASSERT_TRUE(last.has_value());
  scans.push_back(*last);
  ASSERT_EQ(scans.size(), 4u);
  EXPECT_TRUE(scans[0].partial);
  EXPECT_FALSE(scans[1].partial);
  EXPECT_FALSE(scans[2].partial);
  EXPECT_TRUE(scans[3].partial);
  for (std::size_t s = 0; s < scans.size(); ++s) EXPECT_EQ(scans[s].index, s);
  const auto& full = scans[1];
  ASSERT_EQ(full.rings.size(), 16u);
  for (const auto& ring : full.rings) {
    // Every firing of the turn is in every ring, whatever came back.
    EXPECT_NEAR(static_cast<double>(ring.returns.size()), per_turn, 2.0);
    EXPECT_EQ(kCalibration.lasers[ring.channel].ring, ring.ring);
    EXPECT_TRUE(
        std::is_sorted(ring.returns.begin(), ring.returns.end(),
                       [](const auto& a, const auto& b) { return a.azimuth_rad < b.azimuth_rad; }));
    const auto expected = ring.channel == 3   ? sensor::ReturnStatus::NoReturn
                          : ring.channel == 4 ? sensor::ReturnStatus::OutOfRange
                                              : sensor::ReturnStatus::Valid;
    for (const auto& ret : ring.returns) ASSERT_EQ(ret.status, expected);
  }
  EXPECT_NEAR(full.end_time_s - full.start_time_s, 0.1, 2e-4);
  // Rings are ranked by elevation: ring 0 is the lowest beam (−15°).
  EXPECT_DOUBLE_EQ(full.rings[0].elevation_rad, -15.0 * M_PI / 180.0);
  std::size_t valid = 0;
  for (const auto& ring : full.rings)
    valid += ring.channel == 3 || ring.channel == 4 ? 0 : ring.returns.size();
  EXPECT_EQ(full.valid_returns(), valid);
}

TEST(ScanAssembler, CutsAtTheConfiguredAzimuth) {
  const double cut = M_PI / 2;  // left of the sensor
  const auto points = spin(24 * 160, 0.3);
  ScanAssemblerConfig config;
  config.cut_azimuth_rad = cut;
  ScanAssembler assembler(kCalibration, config);
  std::vector<sensor::Scan> scans;
  assembler.add(points, scans);
  ASSERT_GE(scans.size(), 2u);
  // The clockwise sweep of a full scan starts just below the cut (in θ) and ends just above it:
  // the first firing in time is at θ ≈ cut, the last at θ ≈ cut + one step.
  const auto& ring = scans[1].rings[8].returns;
  const auto first = std::min_element(
      ring.begin(), ring.end(), [](const auto& a, const auto& b) { return a.time_s < b.time_s; });
  const auto last = std::max_element(
      ring.begin(), ring.end(), [](const auto& a, const auto& b) { return a.time_s < b.time_s; });
  EXPECT_NEAR(std::remainder(first->azimuth_rad - cut, 2 * M_PI), 0.0, 0.01);
  EXPECT_NEAR(std::remainder(last->azimuth_rad - cut, 2 * M_PI), 0.0, 0.01);
  EXPECT_LE(std::remainder(first->azimuth_rad - cut, 2 * M_PI), 1e-9);
}

TEST(ScanAssembler, SilenceEndsAScanAsPartial) {
  auto points = spin(24 * 20, 3.0);  // a quarter turn that does not reach the cut at θ = 0
  const auto later = spin(24 * 20, 3.0, 5.0);  // resumes 5 s later at the same azimuth
  points.insert(points.end(), later.begin(), later.end());
  ScanAssembler assembler(kCalibration);
  std::vector<sensor::Scan> scans;
  assembler.add(points, scans);
  ASSERT_EQ(scans.size(), 1u);
  EXPECT_TRUE(scans[0].partial);
  EXPECT_LT(scans[0].end_time_s, 1.0);
  const auto rest = assembler.finish();
  ASSERT_TRUE(rest.has_value());
  EXPECT_GE(rest->start_time_s, 5.0);
}

TEST(ScanAssembler, DualReturnsKeepBothEchoesLabelled) {
  EXPECT_EQ(return_kind(velodyne::ReturnLabel::DualLast), sensor::ReturnKind::Last);
  EXPECT_EQ(return_kind(velodyne::ReturnLabel::DualBoth), sensor::ReturnKind::Last);
  EXPECT_EQ(return_kind(velodyne::ReturnLabel::DualStrongest), sensor::ReturnKind::Dual);
  EXPECT_EQ(return_kind(velodyne::ReturnLabel::Strongest), sensor::ReturnKind::Strongest);
}

}  // namespace
}  // namespace conicloc::io
