// Encode → write pcap → read → decode gives back the returns (2 mm, 0.01°, 1 µs); frame checksums.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>

#include "io/packet_encoder.hpp"
#include "io/pcap_reader.hpp"
#include "io/pcap_writer.hpp"
#include "io/velodyne_decoder.hpp"
#include "io/velodyne_stream.hpp"
#include "sensor/builtin_calibration.hpp"
#include "test/temp_path.hpp"

namespace conicloc::io {
namespace {

constexpr double kRpm = 600.0;
constexpr double kOmegaRadPerS = kRpm / 60.0 * 2.0 * M_PI;
constexpr double kDeviceStartS = 3599.95;  // crosses the top of the hour: stamps wrap
constexpr double kUtcStartS = 1.7e9;

struct Truth {
  double azimuth_rad, range_m, time_s;
  std::uint8_t intensity;
};

std::string temp_path(const std::string& name) {
  return conicloc::test::unique_temp_path("io_" + name).string();
}

double wrap_2pi(double a) {
  a = std::fmod(a, 2 * M_PI);
  return a < 0 ? a + 2 * M_PI : a;
}

double angle_diff(double a, double b) {
  return std::remainder(a - b, 2 * M_PI);
}

// Sequences of a sensor turning clockwise at kRpm; truth per channel (firing time and azimuth).
std::vector<FiringSequence> make_sequences(int count, std::vector<Truth>& truth, std::mt19937& rng,
                                           const velodyne::PacketLayout& layout) {
  std::uniform_real_distribution<double> range(0.4, 120.0);
  std::uniform_int_distribution<int> intensity(0, 255);
  std::vector<FiringSequence> sequences;
  for (int i = 0; i < count; ++i) {
    FiringSequence s;
    s.time_s = kDeviceStartS + i * layout.sequence_period_us * 1e-6;
    s.azimuth_rad = 1.0 - kOmegaRadPerS * (s.time_s - kDeviceStartS);
    for (int k = 0; k < layout.channels; ++k) {
      s.range_m[k] = (i + k) % 7 == 0 ? 0.0 : range(rng);
      s.intensity[k] = static_cast<std::uint8_t>(intensity(rng));
      const double dt = layout.firing_offset_us(0, k) * 1e-6;
      truth.push_back({wrap_2pi(s.azimuth_rad - kOmegaRadPerS * dt), s.range_m[k], s.time_s + dt,
                       s.intensity[k]});
    }
    sequences.push_back(s);
  }
  return sequences;
}

TEST(PcapRoundTrip, EncodeWriteReadDecodeGivesTheReturnsBack) {
  std::mt19937 rng(7);
  const auto calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  PacketEncoder encoder({.model = sensor::SensorModel::VLP16});
  std::vector<Truth> truth;
  const auto sequences = make_sequences(24 * 50, truth, rng, encoder.layout());
  const std::string path = temp_path("roundtrip.pcap");
  {
    PcapWriter writer(path);
    for (const auto& s : sequences) encoder.add(s);
    encoder.flush();
    for (const auto& packet : encoder.take_packets()) {
      writer.write_udp(packet.payload, kUtcStartS + packet.time_s - kDeviceStartS);
    }
    writer.close();
    EXPECT_EQ(writer.packets_written(), 50u);
  }
  PcapReader reader(path, {velodyne::kDataPort});
  VelodyneDecoder decoder(calibration);
  std::vector<DecodedPoint> points;
  double previous_capture_s = 0.0;
  double hours_s = 0.0;
  std::uint32_t previous_stamp = 0;
  while (auto datagram = reader.next()) {
    ASSERT_EQ(decoder.check(datagram->payload), PacketCheck::Ok);
    EXPECT_GT(datagram->capture_time_s, previous_capture_s);
    previous_capture_s = datagram->capture_time_s;
    const std::uint32_t stamp = VelodyneDecoder::timestamp_us(datagram->payload);
    if (stamp < previous_stamp) hours_s += 3600.0;  // the device clock wrapped
    previous_stamp = stamp;
    decoder.decode(datagram->payload, stamp * 1e-6 + hours_s, points);
  }
  EXPECT_EQ(reader.counts().records, 50u);
  EXPECT_EQ(reader.counts().udp_datagrams, 50u);
  ASSERT_EQ(points.size(), truth.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& p = points[i];
    const auto& t = truth[i];
    ASSERT_NEAR(p.range_m, t.range_m, 0.001 + 1e-5) << "point " << i;  // 2 mm units, float
    ASSERT_EQ(p.intensity, t.intensity) << "point " << i;
    ASSERT_NEAR(angle_diff(p.azimuth_rad, t.azimuth_rad), 0.0, 0.01 * M_PI / 180) << "point " << i;
    ASSERT_NEAR(p.time_s, t.time_s, 1e-6) << "point " << i;
    const int channel = static_cast<int>(i % 16);
    ASSERT_EQ(p.channel, channel);
    // The point lies on laser k's ray at the decoded range.
    const auto& laser = calibration.lasers[channel];
    const double z =
        p.range_m > 0 ? p.range_m * std::sin(laser.elevation_rad) + laser.vertical_offset_m : 0.0;
    ASSERT_NEAR(p.z_m, z, 1e-4);
    ASSERT_NEAR(std::hypot(p.x_m, p.y_m), p.range_m * std::cos(laser.elevation_rad), 1e-4);
  }
  std::filesystem::remove(path);
}

TEST(PcapRoundTrip, PacketWithoutAnyReturnIsGoodData) {
  // Facing open space (an open door to outside), every distance is 0: the packet is valid and its
  // firings decode as no-returns; only a blank payload is a reject.
  const auto calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  PacketEncoder encoder({.model = sensor::SensorModel::VLP16});
  std::mt19937 rng(5);
  std::vector<Truth> truth;
  auto sequences = make_sequences(24, truth, rng, encoder.layout());
  for (auto& s : sequences) {
    for (auto& r : s.range_m) r = 0.0;
    for (auto& i : s.intensity) i = 0;
    encoder.add(s);
  }
  encoder.flush();
  const auto packets = encoder.take_packets();
  ASSERT_EQ(packets.size(), 1u);
  VelodyneDecoder decoder(calibration);
  EXPECT_EQ(decoder.check(packets[0].payload), PacketCheck::Ok);
  std::vector<DecodedPoint> points;
  decoder.decode(packets[0].payload, 0.0, points);
  EXPECT_EQ(points.size(), 24u * 16u);
  for (const auto& p : points) EXPECT_EQ(p.range_m, 0.0);
  EXPECT_EQ(decoder.check(std::vector<std::uint8_t>(velodyne::kDataPacketBytes, 0)),
            PacketCheck::AllZero);
}

TEST(PcapRoundTrip, TwoSensorsOnOnePortAreToldApartByTheirAddress) {
  // Two sensors both sending to port 2368, one from .201 (every range 5 m), one from .202 (9 m),
  // their packets interleaved: the reader reports each sender, and a stream asked for .202
  // decodes its packets only, counting the others.
  const auto calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  const std::string path = temp_path("two_sensors.pcap");
  PcapWriter writer(path);
  UdpEndpoints second;
  second.src_ip = {192, 168, 1, 202};
  std::size_t per_sensor = 0;
  for (const double range : {5.0, 9.0}) {
    PacketEncoder encoder({.model = sensor::SensorModel::VLP16});
    std::mt19937 rng(7);
    std::vector<Truth> truth;
    for (auto& sequence : make_sequences(240, truth, rng, encoder.layout())) {
      for (auto& r : sequence.range_m) r = range;
      encoder.add(sequence);
    }
    encoder.flush();
    const auto packets = encoder.take_packets();
    per_sensor = packets.size();
    // Written one sensor after the other here; what matters is who sent each.
    for (const auto& packet : packets) {
      writer.write_udp(packet.payload, kUtcStartS + packet.time_s,
                       range == 5.0 ? UdpEndpoints{} : second);
    }
  }
  writer.close();
  ASSERT_GT(per_sensor, 5u);

  PcapReader reader(path, {velodyne::kDataPort});
  std::size_t from_second = 0;
  while (const auto datagram = reader.next()) {
    EXPECT_TRUE(datagram->src_address == 0xC0A801C9u || datagram->src_address == 0xC0A801CAu);
    from_second += datagram->src_address == 0xC0A801CAu;
  }
  EXPECT_EQ(from_second, per_sensor);

  PcapReader again(path, {velodyne::kDataPort});
  VelodyneStream stream(again, calibration, {.source_address = 0xC0A801CAu});
  std::vector<DecodedPoint> points;
  std::size_t valid = 0;
  while (stream.next(points)) {
    for (const auto& p : points) {
      if (p.range_m == 0.0) continue;
      EXPECT_NEAR(p.range_m, 9.0, 0.002);
      ++valid;
    }
  }
  EXPECT_EQ(stream.stats().data_packets, per_sensor);
  EXPECT_EQ(stream.stats().other_senders, per_sensor);
  EXPECT_GT(valid, 0u);
  std::remove(path.c_str());
}

TEST(PcapRoundTrip, DualReturnPairsComeBackLabelledAndIdenticalPairsOnce) {
  std::mt19937 rng(3);
  const auto calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  PacketEncoder encoder(
      {.model = sensor::SensorModel::VLP16, .return_mode = velodyne::ReturnMode::Dual});
  EXPECT_EQ(encoder.sequences_per_packet(), 12);
  std::vector<Truth> truth;
  auto sequences = make_sequences(12, truth, rng, encoder.layout());
  for (auto& s : sequences) {
    for (int k = 0; k < 16; ++k) {
      // Odd channels see a second, stronger echo before the last one; even channels one echo.
      if (k % 2 == 1 && s.range_m[k] > 1.0) {
        s.second_range_m[k] = s.range_m[k] - 0.5;
        s.second_intensity[k] = 250;
      }
    }
    encoder.add(s);
  }
  const auto packets = encoder.take_packets();
  ASSERT_EQ(packets.size(), 1u);
  EXPECT_EQ(packets[0].payload[velodyne::kReturnModeOffset], 0x39);
  VelodyneDecoder decoder(calibration);
  ASSERT_EQ(decoder.check(packets[0].payload), PacketCheck::Ok);
  std::vector<DecodedPoint> points;
  decoder.decode(packets[0].payload, 0.0, points);
  std::size_t index = 0;
  for (const auto& s : sequences) {
    for (int k = 0; k < 16; ++k) {
      ASSERT_LT(index, points.size());
      const bool pair = s.second_range_m[k] > 0;
      EXPECT_EQ(points[index].label,
                pair ? velodyne::ReturnLabel::DualLast : velodyne::ReturnLabel::DualBoth);
      EXPECT_NEAR(points[index].range_m, s.range_m[k], 0.0011);
      ++index;
      if (pair) {  // the strongest echo follows the last one, at the same firing time and azimuth
        EXPECT_EQ(points[index].label, velodyne::ReturnLabel::DualStrongest);
        EXPECT_NEAR(points[index].range_m, s.second_range_m[k], 0.0011);
        EXPECT_EQ(points[index].intensity, 250);
        EXPECT_EQ(points[index].time_s, points[index - 1].time_s);
        EXPECT_EQ(points[index].azimuth_rad, points[index - 1].azimuth_rad);
        ++index;
      }
    }
  }
  EXPECT_EQ(index, points.size());
}

TEST(PcapWriter, FramesHaveValidIpv4AndUdpChecksumsAndLengths) {
  std::vector<std::uint8_t> payload(1206);
  for (std::size_t i = 0; i < payload.size(); ++i) payload[i] = static_cast<std::uint8_t>(i * 31);
  const auto frame = make_udp_frame(payload, UdpEndpoints{}, 77);
  ASSERT_EQ(frame.size(), 14u + 20u + 8u + 1206u);
  const std::uint8_t* ip = frame.data() + 14;
  EXPECT_EQ(ip[2] << 8 | ip[3], 20 + 8 + 1206);
  // A correct header sums to 0xFFFF including its checksum (RFC 1071).
  EXPECT_EQ(ones_complement_sum(std::span(ip, 20)), 0xFFFFu);
  const std::uint8_t* udp = ip + 20;
  EXPECT_EQ(udp[0] << 8 | udp[1], 2368);
  EXPECT_EQ(udp[4] << 8 | udp[5], 8 + 1206);
  std::uint32_t sum = ones_complement_sum(std::span(ip + 12, 8));
  sum += 17 + 8 + 1206;
  sum = ones_complement_sum(std::span(udp, 8 + 1206), sum);
  EXPECT_EQ(sum, 0xFFFFu);
  EXPECT_EQ(ip[12], 192);
  EXPECT_EQ(ip[15], 201);
  EXPECT_EQ(ip[16], 255);
}

TEST(PcapWriter, TcpdumpReadsEveryPacketWithoutErrors) {
  const char* tcpdump = std::filesystem::exists("/usr/sbin/tcpdump")  ? "/usr/sbin/tcpdump"
                        : std::filesystem::exists("/usr/bin/tcpdump") ? "/usr/bin/tcpdump"
                                                                      : nullptr;
  if (!tcpdump) GTEST_SKIP() << "tcpdump not installed";
  std::mt19937 rng(11);
  PacketEncoder encoder;
  std::vector<Truth> truth;
  const std::string path = temp_path("tcpdump.pcap");
  {
    PcapWriter writer(path);
    for (const auto& s : make_sequences(24 * 20, truth, rng, encoder.layout())) encoder.add(s);
    for (const auto& packet : encoder.take_packets())
      writer.write_udp(packet.payload, kUtcStartS + packet.time_s);
  }
  const std::string out = temp_path("tcpdump.txt");
  const std::string command = std::string(tcpdump) + " -nn -vv -r " + path + " > " + out + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::FILE* file = std::fopen(out.c_str(), "r");
  ASSERT_NE(file, nullptr);
  char line[512];
  int packets = 0;
  int bad = 0;
  while (std::fgets(line, sizeof line, file)) {
    const std::string text(line);
    if (text.find("UDP, length 1206") != std::string::npos) ++packets;
    if (text.find("bad") != std::string::npos || text.find("truncated") != std::string::npos) ++bad;
  }
  std::fclose(file);
  EXPECT_EQ(packets, 20);
  EXPECT_EQ(bad, 0);
  std::filesystem::remove(path);
  std::filesystem::remove(out);
}

}  // namespace
}  // namespace conicloc::io
