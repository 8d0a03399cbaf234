// Bad captures: every bad record or packet is counted by reason and skipped, every good packet
// before and after it is decoded; a file that is not a capture is an InputError (and the tool
// exits non-zero).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "io/input_error.hpp"
#include "io/packet_encoder.hpp"
#include "io/pcap_reader.hpp"
#include "io/pcap_writer.hpp"
#include "io/velodyne_stream.hpp"
#include "sensor/builtin_calibration.hpp"
#include "test/temp_path.hpp"

namespace conicloc::io {
namespace {

using Bytes = std::vector<std::uint8_t>;

std::string temp_path(const std::string& name) {
  return conicloc::test::unique_temp_path("bad_" + name).string();
}

// Good VLP-16 packets at 600 rpm, one wall at 5 m; packet i starts at 55.296 µs · 24 · i.
std::vector<EncodedPacket> good_packets(int count) {
  PacketEncoder encoder;
  for (int i = 0; i < count * 24; ++i) {
    FiringSequence s;
    s.time_s = 100.0 + i * 55.296e-6;
    s.azimuth_rad = 0.5 - 2 * M_PI * 10.0 * (s.time_s - 100.0);
    for (int k = 0; k < 16; ++k) {
      s.range_m[k] = 5.0 + 0.01 * k;
      s.intensity[k] = 50;
    }
    encoder.add(s);
  }
  return encoder.take_packets();
}

// A classic pcap built byte by byte, so records can be cut and lengths falsified.
class RawPcap {
 public:
  RawPcap() {
    const Bytes header = {0xD4, 0xC3, 0xB2, 0xA1, 2,    0,    4, 0, 0, 0, 0, 0,
                          0,    0,    0,    0,    0xFF, 0xFF, 0, 0, 1, 0, 0, 0};
    bytes_ = header;
  }
  void record(const Bytes& frame, std::size_t captured, double time_s) {
    put32(static_cast<std::uint32_t>(time_s));
    put32(static_cast<std::uint32_t>(std::fmod(time_s, 1.0) * 1e6));
    put32(static_cast<std::uint32_t>(captured));
    put32(static_cast<std::uint32_t>(frame.size()));
    bytes_.insert(bytes_.end(), frame.begin(), frame.begin() + static_cast<long>(captured));
  }
  void udp(const Bytes& payload, double time_s, std::uint16_t port = 2368) {
    UdpEndpoints endpoints;
    endpoints.dst_port = port;
    const Bytes frame = make_udp_frame(payload, endpoints);
    record(frame, frame.size(), time_s);
  }
  void save(const std::string& path, std::size_t cut_tail = 0) const {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes_.data()),
              static_cast<std::streamsize>(bytes_.size() - cut_tail));
  }

 private:
  void put32(std::uint32_t v) {
    for (int i = 0; i < 4; ++i) bytes_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  Bytes bytes_;
};

Bytes payload_of(const EncodedPacket& packet) {
  return Bytes(packet.payload.begin(), packet.payload.end());
}

struct Decoded {
  std::vector<std::uint32_t> stamps;
  StreamStats stats;
  CaptureCounts counts;
};

Decoded decode_file(const std::string& path) {
  PcapReader reader(path, {velodyne::kDataPort, velodyne::kPositionPort});
  VelodyneStream stream(reader, sensor::builtin_calibration(sensor::SensorModel::VLP16));
  Decoded decoded;
  std::vector<DecodedPoint> points;
  while (stream.next(points)) {
    EXPECT_EQ(points.size(), 384u);
    EXPECT_NEAR(points[0].range_m, 5.0, 0.002);
    decoded.stamps.push_back(
        static_cast<std::uint32_t>(std::llround((points[0].time_s - 0.0) * 1e6)));
  }
  decoded.stats = stream.stats();
  decoded.counts = reader.counts();
  return decoded;
}

std::size_t rejected(const StreamStats& stats, PacketCheck reason) {
  return stats.rejected[static_cast<std::size_t>(reason)];
}

TEST(PcapBadInput, EveryBadPacketIsCountedByReasonAndEveryGoodOneDecoded) {
  const auto good = good_packets(12);
  RawPcap pcap;
  double t = 1000.0;
  auto next_time = [&] { return t += 0.001; };
  std::vector<std::uint32_t> expected;
  auto add_good = [&](int i) {
    pcap.udp(payload_of(good[i]), next_time());
    expected.push_back(velodyne::read_u32(good[i].payload.data() + velodyne::kTimestampOffset));
  };
  add_good(0);
  pcap.udp(payload_of(good[1]), next_time(), 9999);  // foreign port
  add_good(1);
  Bytes arp(60, 0);  // not IPv4
  arp[12] = 0x08;
  arp[13] = 0x06;
  pcap.record(arp, arp.size(), next_time());
  add_good(2);
  pcap.udp(Bytes(1000, 0x11), next_time());  // wrong size
  add_good(3);
  Bytes flag = payload_of(good[4]);
  flag[velodyne::block_offset(5)] = 0x00;  // bad block flag
  pcap.udp(flag, next_time());
  add_good(4);
  pcap.udp(Bytes(velodyne::kDataPacketBytes, 0), next_time());  // all zero
  add_good(5);
  Bytes jump = payload_of(good[6]);
  velodyne::write_u16(jump.data() + velodyne::block_offset(7) + 2, 9000);  // azimuth jump
  pcap.udp(jump, next_time());
  add_good(6);
  Bytes repeat = payload_of(good[7]);
  const std::uint16_t az3 = velodyne::read_u16(repeat.data() + velodyne::block_offset(3) + 2);
  velodyne::write_u16(repeat.data() + velodyne::block_offset(4) + 2, az3);  // azimuth repeat
  pcap.udp(repeat, next_time());
  add_good(7);
  pcap.udp(payload_of(good[7]), next_time());  // duplicate of the previous
  add_good(8);
  {
    UdpEndpoints endpoints;
    const Bytes frame = make_udp_frame(payload_of(good[9]), endpoints);
    pcap.record(frame, 600, next_time());  // snap length cut
  }
  add_good(9);
  pcap.udp(payload_of(good[3]), next_time());  // time goes backwards
  add_good(10);
  pcap.udp(Bytes(512, 0), next_time(), velodyne::kPositionPort);  // a position packet
  pcap.udp(Bytes(100, 0), next_time(), velodyne::kPositionPort);  // a short position packet
  add_good(11);
  pcap.udp(payload_of(good[0]), next_time());  // the last record, cut short
  const std::string path = temp_path("mixed.pcap");
  pcap.save(path, 300);

  const Decoded decoded = decode_file(path);
  EXPECT_EQ(decoded.stats.data_packets, expected.size());
  ASSERT_EQ(decoded.stamps.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(decoded.stamps[i], expected[i]);
  EXPECT_EQ(decoded.counts.foreign_port, 1u);
  EXPECT_EQ(decoded.counts.not_ipv4_udp, 1u);
  EXPECT_EQ(decoded.counts.snap_length_cut, 1u);
  EXPECT_EQ(decoded.counts.truncated_records, 1u);
  EXPECT_FALSE(decoded.counts.stop_message.empty());
  EXPECT_EQ(rejected(decoded.stats, PacketCheck::WrongSize), 1u);
  EXPECT_EQ(rejected(decoded.stats, PacketCheck::BadBlockFlag), 1u);
  EXPECT_EQ(rejected(decoded.stats, PacketCheck::AllZero), 1u);
  EXPECT_EQ(rejected(decoded.stats, PacketCheck::AzimuthJump), 1u);
  EXPECT_EQ(rejected(decoded.stats, PacketCheck::AzimuthRepeat), 1u);
  EXPECT_EQ(rejected(decoded.stats, PacketCheck::Duplicate), 1u);
  EXPECT_EQ(rejected(decoded.stats, PacketCheck::TimeBackwards), 1u);
  EXPECT_EQ(decoded.stats.rejected_total(), 7u);
  EXPECT_EQ(decoded.stats.position_packets, 1u);
  EXPECT_EQ(decoded.stats.bad_position_packets, 1u);
  std::filesystem::remove(path);
}

TEST(PcapBadInput, NotACaptureIsAnInputErrorNamingTheFile) {
  const std::string path = temp_path("text.pcap");
  std::ofstream(path) << "scan,ring,azimuth_deg\n1,2,3\n";
  try {
    PcapReader reader(path);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_NE(std::string(e.what()).find("not a readable pcap"), std::string::npos);
  }
  EXPECT_THROW(PcapReader(temp_path("does_not_exist.pcap")), InputError);
  std::filesystem::remove(path);
}

TEST(PcapBadInput, TruncatedFileHeaderIsAnInputError) {
  const std::string path = temp_path("header.pcap");
  RawPcap().save(path, 10);  // 14 of the 24 header bytes
  EXPECT_THROW(PcapReader reader(path), InputError);
  std::filesystem::remove(path);
}

TEST(PcapBadInput, FileCutInsideTheFirstRecordDecodesNothingAndSaysSo) {
  const auto good = good_packets(1);
  RawPcap pcap;
  pcap.udp(payload_of(good[0]), 1.0);
  const std::string path = temp_path("cut.pcap");
  pcap.save(path, 500);
  const Decoded decoded = decode_file(path);
  EXPECT_EQ(decoded.stats.data_packets, 0u);
  EXPECT_EQ(decoded.counts.truncated_records, 1u);
  std::filesystem::remove(path);
}

TEST(PcapBadInput, DecodeToolExitsNonZeroOnANonCapture) {
  const std::string path = temp_path("notes.txt");
  std::ofstream(path) << "hello\n";
  const std::string command =
      std::string(CONICLOC_BINARY) + " decode " + path + " > /dev/null 2>&1";
  const int status = std::system(command.c_str());
  EXPECT_NE(status, 0);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace conicloc::io
