// One test per timing rule: azimuth interpolation per firing, firing times per model, dual-return
// ordering, and the hourly wrap of the device clock giving monotonic times.
#include <gtest/gtest.h>

#include <cmath>

#include "io/packet_encoder.hpp"
#include "io/scan_assembler.hpp"
#include "io/velodyne_decoder.hpp"
#include "io/velodyne_stream.hpp"
#include "sensor/builtin_calibration.hpp"

namespace conicloc::io {
namespace {

using Payload = std::array<std::uint8_t, velodyne::kDataPacketBytes>;

// A packet with block azimuths start + step·b (0.01°), every record at `distance` units.
Payload make_packet(int start_cdeg, int step_cdeg, std::uint32_t stamp_us,
                    velodyne::ReturnMode mode = velodyne::ReturnMode::Strongest,
                    std::uint16_t distance = 1000) {
  Payload p{};
  const bool dual = mode == velodyne::ReturnMode::Dual;
  for (int b = 0; b < velodyne::kBlocksPerPacket; ++b) {
    std::uint8_t* block = p.data() + velodyne::block_offset(b);
    block[0] = 0xFF;
    block[1] = 0xEE;
    const int group = dual ? b / 2 : b;
    velodyne::write_u16(block + 2,
                        static_cast<std::uint16_t>((start_cdeg + step_cdeg * group) % 36000));
    for (int r = 0; r < 32; ++r) {
      velodyne::write_u16(block + 4 + 3 * r, distance);
      block[6 + 3 * r] = static_cast<std::uint8_t>(r);
    }
  }
  velodyne::write_u32(p.data() + velodyne::kTimestampOffset, stamp_us);
  p[velodyne::kReturnModeOffset] = static_cast<std::uint8_t>(mode);
  p[velodyne::kProductIdOffset] = 0x22;
  return p;
}

double velodyne_alpha_cdeg(float azimuth_rad) {
  double alpha = -azimuth_rad * 18000.0 / M_PI;
  while (alpha < 0) alpha += 36000.0;
  return alpha;
}

TEST(VelodyneTiming, AzimuthIsInterpolatedPerFiringFromTheBlockStep) {
  const VelodyneDecoder decoder(sensor::builtin_calibration(sensor::SensorModel::VLP16));
  const Payload packet = make_packet(35900, 40, 0);  // crosses 0 at block 3
  ASSERT_EQ(decoder.check(packet), PacketCheck::Ok);
  std::vector<DecodedPoint> points;
  ASSERT_EQ(decoder.decode(packet, 0.0, points), 384u);
  for (int b = 0; b < 12; ++b) {
    for (int s = 0; s < 2; ++s) {
      for (int k = 0; k < 16; ++k) {
        const auto& p = points[static_cast<std::size_t>(b * 32 + s * 16 + k)];
        // VLP-16 manual 9.5: α = α_block + Δ·(55.296 s + 2.304 k)/110.592.
        const double expected =
            std::fmod(35900 + 40 * b + 40 * (55.296 * s + 2.304 * k) / 110.592, 36000.0);
        // azimuth_rad is a float: near 2π its resolution is 4.8e-7 rad = 2.7e-3 (0.01°) units.
        EXPECT_NEAR(std::remainder(velodyne_alpha_cdeg(p.azimuth_rad) - expected, 36000.0), 0.0,
                    6e-3)
            << "block " << b << " sequence " << s << " channel " << k;
        EXPECT_NEAR(p.time_s, (110.592 * b + 55.296 * s + 2.304 * k) * 1e-6, 1e-12);
        EXPECT_EQ(p.channel, k);
      }
    }
  }
}

TEST(VelodyneTiming, RangeOffsetIsAddedToEveryReturnButNotToNoReturn) {
  sensor::LaserCalibration calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  calibration.lasers[5].range_offset_m = 0.0375;
  calibration.lasers[6].range_offset_m = -0.0125;
  const VelodyneDecoder decoder(calibration);
  std::vector<DecodedPoint> points;
  decoder.decode(make_packet(1000, 40, 0, velodyne::ReturnMode::Strongest, 1000), 0.0, points);
  const double cos5 = std::cos(calibration.lasers[5].elevation_rad);
  for (const auto& p : points) {
    const double expected = 2.0 + calibration.lasers[p.channel].range_offset_m;  // 1000 × 2 mm
    EXPECT_NEAR(p.range_m, expected, 1e-6) << "channel " << int{p.channel};
    if (p.channel == 5) {
      EXPECT_NEAR(std::hypot(p.x_m, p.y_m), expected * cos5, 1e-5);
    }
  }
  points.clear();
  decoder.decode(make_packet(1000, 40, 0, velodyne::ReturnMode::Strongest, 0), 0.0, points);
  for (const auto& p : points) EXPECT_EQ(p.range_m, 0.0f);
}

TEST(VelodyneTiming, ThirtyTwoLaserModelsFireOnTheirOwnSchedules) {
  std::vector<DecodedPoint> points;
  const VelodyneDecoder hdl(sensor::builtin_calibration(sensor::SensorModel::HDL32E));
  hdl.decode(make_packet(0, 20, 0), 0.0, points);
  ASSERT_EQ(points.size(), 384u);
  EXPECT_NEAR(points[31].time_s, 31 * 1.152e-6, 1e-12);  // one laser every 1.152 µs
  EXPECT_NEAR(points[32].time_s, 46.08e-6, 1e-12);       // one block every 46.08 µs
  EXPECT_NEAR(velodyne_alpha_cdeg(points[31].azimuth_rad), 20 * 31 * 1.152 / 46.08, 6e-3);
  points.clear();
  const auto vlp32c_calibration = sensor::builtin_calibration(sensor::SensorModel::VLP32C);
  const VelodyneDecoder vlp32c(vlp32c_calibration);
  vlp32c.decode(make_packet(1000, 20, 0), 0.0, points);
  EXPECT_EQ(points[0].time_s, points[1].time_s);  // lasers fire in pairs
  EXPECT_NEAR(points[2].time_s, 2.304e-6, 1e-12);
  EXPECT_NEAR(points[32].time_s, 55.296e-6, 1e-12);
  EXPECT_NEAR(points[5].range_m, 1000 * 0.004, 1e-6);  // 4 mm distance unit
  // Laser 0 looks 1.4° clockwise of the firing azimuth (VLP-32C manual).
  EXPECT_NEAR(velodyne_alpha_cdeg(points[0].azimuth_rad), 1000 + 140, 1e-2);
}

TEST(VelodyneTiming, DualReturnPairsAreLastThenStrongestAndIdenticalPairsOnce) {
  const VelodyneDecoder decoder(sensor::builtin_calibration(sensor::SensorModel::VLP16));
  Payload packet = make_packet(100, 40, 0, velodyne::ReturnMode::Dual);
  // Block 1 (strongest) differs from block 0 (last) in record 5 only.
  velodyne::write_u16(packet.data() + velodyne::block_offset(1) + 4 + 3 * 5, 700);
  ASSERT_EQ(decoder.check(packet), PacketCheck::Ok);
  std::vector<DecodedPoint> points;
  decoder.decode(packet, 0.0, points);
  // 6 pairs × 32 records, each once, plus one extra for the differing record.
  ASSERT_EQ(points.size(), 6u * 32u + 1u);
  for (int r = 0; r < 5; ++r) EXPECT_EQ(points[r].label, velodyne::ReturnLabel::DualBoth);
  EXPECT_EQ(points[5].label, velodyne::ReturnLabel::DualLast);
  EXPECT_NEAR(points[5].range_m, 2.0, 1e-6);
  EXPECT_EQ(points[6].label, velodyne::ReturnLabel::DualStrongest);
  EXPECT_NEAR(points[6].range_m, 1.4, 1e-6);
  EXPECT_EQ(points[6].time_s, points[5].time_s);
  EXPECT_EQ(points[6].channel, points[5].channel);
  // Pairs follow each other every 110.592 µs (dual mode halves the azimuth rate per packet).
  EXPECT_NEAR(points[33].time_s, 110.592e-6, 1e-12);
  // Pair blocks must share their azimuth.
  velodyne::write_u16(packet.data() + velodyne::block_offset(3) + 2, 7);
  EXPECT_EQ(decoder.check(packet), PacketCheck::AzimuthJump);
}

class ListSource : public DatagramSource {
 public:
  explicit ListSource(std::vector<Payload> packets) : packets_(std::move(packets)) {}
  std::optional<UdpDatagram> next() override {
    if (index_ == packets_.size()) return std::nullopt;
    UdpDatagram d;
    d.payload = packets_[index_];
    d.dst_port = velodyne::kDataPort;
    d.record = ++index_;
    return d;
  }
  std::string name() const override { return "list"; }

 private:
  std::vector<Payload> packets_;
  std::size_t index_ = 0;
};

TEST(VelodyneTiming, HourWrapOfTheDeviceClockGivesMonotonicTimes) {
  // 600 rpm, one packet every 1327.104 µs; the device clock passes 3 600 000 000 µs → 0.
  std::vector<Payload> packets;
  const double period_us = 12 * 110.592;
  for (int i = 0; i < 400; ++i) {
    const double t_us = 3'600'000'000.0 - 200 * period_us + i * period_us;
    const auto stamp = static_cast<std::uint32_t>(std::fmod(t_us, 3.6e9));
    packets.push_back(make_packet((i * 12 * 40) % 36000, 40, stamp));
  }
  ListSource source(packets);
  VelodyneStream stream(source, sensor::builtin_calibration(sensor::SensorModel::VLP16));
  ScanAssembler assembler(sensor::builtin_calibration(sensor::SensorModel::VLP16));
  std::vector<DecodedPoint> points;
  std::vector<sensor::Scan> scans;
  double previous = -1.0;
  while (stream.next(points)) {
    for (const auto& p : points) {
      ASSERT_GE(p.time_s, previous);
      previous = p.time_s;
    }
    assembler.add(points, scans);
  }
  EXPECT_EQ(stream.stats().data_packets, 400u);
  EXPECT_EQ(stream.stats().clock_wraps, 1u);
  EXPECT_EQ(stream.stats().rejected_total(), 0u);
  EXPECT_EQ(stream.stats().packets_lost, 0u);
  EXPECT_NEAR(stream.stats().last_time_s - stream.stats().first_time_s, 399 * period_us * 1e-6,
              1e-6);
  EXPECT_GT(previous, 3600.0);  // past the wrap the clock keeps counting up
  ASSERT_GE(scans.size(), 2u);
  for (std::size_t s = 1; s < scans.size(); ++s) {
    EXPECT_GT(scans[s].start_time_s, scans[s - 1].end_time_s);
  }
}

}  // namespace
}  // namespace conicloc::io
