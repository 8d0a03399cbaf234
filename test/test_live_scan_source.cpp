// io::LiveScanSource on loopback: the scans of packets sent over UDP are the scans of the same
// packets read from a capture; garbage datagrams are named (number, sender) and change nothing
// else; a consumer that falls behind loses whole scans, counted; position packets are read on
// their own socket; endpoints and bind failures are reported by name.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <thread>

#include "io/input_error.hpp"
#include "io/live_scan_source.hpp"
#include "io/packet_encoder.hpp"
#include "io/pcap_writer.hpp"
#include "io/udp_sender.hpp"
#include "sensor/builtin_calibration.hpp"
#include "test/temp_path.hpp"

namespace conicloc::io {
namespace {

constexpr std::uint32_t kLoopback = 0x7f000001;  // 127.0.0.1

// 400 VLP-16 packets at 600 rpm: 5.3 turns, so four whole scans between two partial ones.
std::vector<EncodedPacket> packets() {
  PacketEncoder encoder;
  for (int i = 0; i < 400 * 24; ++i) {
    FiringSequence s;
    s.time_s = 10.0 + i * 55.296e-6;
    s.azimuth_rad = 2.0 - 2 * M_PI * 10.0 * i * 55.296e-6;
    for (int k = 0; k < 16; ++k) {
      s.range_m[k] = 3.0 + 0.1 * k + 0.5 * std::sin(0.01 * i);
      s.intensity[k] = static_cast<std::uint8_t>(i % 200);
    }
    encoder.add(s);
  }
  return encoder.take_packets();
}

const sensor::LaserCalibration& vlp16() {
  static const auto calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  return calibration;
}

std::vector<sensor::Scan> scans_from_capture(const std::vector<EncodedPacket>& sent) {
  const auto path = test::unique_temp_path("live_reference.pcap");
  {
    PcapWriter writer(path.string());
    for (const auto& p : sent) writer.write_udp(p.payload, 1.7e9 + p.time_s);
  }
  auto source = open_scan_source(path.string(), vlp16());
  std::vector<sensor::Scan> scans;
  while (auto scan = source->next()) scans.push_back(std::move(*scan));
  std::filesystem::remove(path);
  return scans;
}

// Sends like a sensor, in bursts short enough for the socket buffer whatever the receiver's
// scheduling (a VLP-16 sends 754 packets a second; this sends ~10× that).
void send_paced(std::uint16_t port, const std::vector<std::vector<std::uint8_t>>& datagrams) {
  UdpSender sender({"127.0.0.1", port});
  for (std::size_t i = 0; i < datagrams.size(); ++i) {
    sender.send(datagrams[i]);
    if (i % 20 == 19) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

std::vector<std::vector<std::uint8_t>> payloads(const std::vector<EncodedPacket>& sent) {
  std::vector<std::vector<std::uint8_t>> out;
  for (const auto& p : sent) out.emplace_back(p.payload.begin(), p.payload.end());
  return out;
}

void expect_same_scan(const sensor::Scan& live, const sensor::Scan& file) {
  EXPECT_EQ(live.index, file.index);
  EXPECT_EQ(live.partial, file.partial);
  EXPECT_EQ(live.start_time_s, file.start_time_s);
  EXPECT_EQ(live.end_time_s, file.end_time_s);
  ASSERT_EQ(live.rings.size(), file.rings.size());
  for (std::size_t r = 0; r < live.rings.size(); ++r) {
    const auto& a = live.rings[r].returns;
    const auto& b = file.rings[r].returns;
    ASSERT_EQ(a.size(), b.size()) << "ring " << r;
    for (std::size_t i = 0; i < a.size(); ++i) {
      ASSERT_EQ(a[i].range_m, b[i].range_m);
      ASSERT_EQ(a[i].azimuth_rad, b[i].azimuth_rad);
      ASSERT_EQ(a[i].time_s, b[i].time_s);
      ASSERT_EQ(a[i].intensity, b[i].intensity);
    }
  }
}

LiveSourceConfig loopback(std::size_t queue_depth) {
  LiveSourceConfig config;
  config.receiver.listen = {"127.0.0.1", 0};
  config.receiver.idle_timeout_s = 0.6;
  config.queue_depth = queue_depth;
  return config;
}

TEST(LiveScanSource, GivesTheScansOfTheSameCaptureReadFromFile) {
  const auto sent = packets();
  const auto reference = scans_from_capture(sent);
  ASSERT_EQ(reference.size(), 6u);
  // Deep enough for every scan: this test compares, the next ones drop.
  LiveScanSource live(vlp16(), loopback(16));
  EXPECT_EQ(live.name(), "udp://127.0.0.1:" + std::to_string(live.port()));
  std::thread sender(send_paced, live.port(), payloads(sent));
  const double before_s =
      std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  std::vector<sensor::Scan> scans;
  std::optional<double> utc_offset_s;
  while (auto scan = live.next()) {
    scans.push_back(std::move(*scan));
    utc_offset_s = live.utc_offset_s();
  }
  sender.join();
  ASSERT_EQ(scans.size(), reference.size());
  for (std::size_t k = 0; k < scans.size(); ++k) expect_same_scan(scans[k], reference[k]);
  EXPECT_EQ(live.dropped_scans(), 0u);
  EXPECT_EQ(live.assembled_scans(), reference.size());
  EXPECT_NEAR(live.rotation_rpm(), 600.0, 1.0);
  // Device time on the host clock: the scans ended after this test started listening.
  ASSERT_TRUE(utc_offset_s.has_value());
  EXPECT_GT(scans.back().end_time_s + *utc_offset_s, before_s);
  EXPECT_EQ(live.counts().udp_datagrams, sent.size());
  EXPECT_EQ(live.stream()->stats().data_packets, sent.size());
}

TEST(LiveScanSource, NamesGarbageDatagramsAndLosesNoGoodData) {
  const auto sent = packets();
  const auto reference = scans_from_capture(sent);
  auto datagrams = payloads(sent);
  std::vector<std::uint8_t> bad_flags = datagrams[100];
  bad_flags[0] = 0x00;  // block flag broken
  // Sent as datagrams 1 ("hi"), 102 (after 100 good packets) and 153.
  datagrams.insert(datagrams.begin() + 150, std::vector<std::uint8_t>(13, 0x42));
  datagrams.insert(datagrams.begin() + 100, bad_flags);
  datagrams.insert(datagrams.begin(), std::vector<std::uint8_t>{'h', 'i'});

  LiveScanSource live(vlp16(), loopback(16));
  std::thread sender(send_paced, live.port(), datagrams);
  std::vector<sensor::Scan> scans;
  while (auto scan = live.next()) scans.push_back(std::move(*scan));
  sender.join();
  ASSERT_EQ(scans.size(), reference.size());
  for (std::size_t k = 0; k < scans.size(); ++k) expect_same_scan(scans[k], reference[k]);

  const auto rejected = live.take_rejections();
  ASSERT_EQ(rejected.size(), 3u);
  EXPECT_EQ(rejected[0].record, 1u);
  EXPECT_EQ(rejected[0].bytes, 2u);
  EXPECT_EQ(rejected[1].record, 102u);
  EXPECT_EQ(rejected[1].bytes, velodyne::kDataPacketBytes);
  EXPECT_EQ(rejected[2].record, 153u);
  EXPECT_EQ(rejected[2].bytes, 13u);
  for (const auto& r : rejected) {
    EXPECT_EQ(r.src_address, kLoopback);
    EXPECT_NE(r.src_port, 0);
    EXPECT_NE(r.check, PacketCheck::Ok);
  }
  EXPECT_TRUE(live.take_rejections().empty());  // each named once
  EXPECT_EQ(live.stream()->stats().rejected_total(), 3u);
  EXPECT_EQ(live.stream()->stats().data_packets, sent.size());
}

TEST(LiveScanSource, AConsumerThatFallsBehindLosesWholeScansCounted) {
  const auto sent = packets();
  const auto reference = scans_from_capture(sent);
  LiveScanSource live(vlp16(), loopback(1));
  std::thread sender(send_paced, live.port(), payloads(sent));
  sender.join();
  // The consumer is busy elsewhere until every scan was assembled (the last one after the idle
  // timeout): the receiver went on without it, keeping the newest.
  for (int waited_ms = 0; live.assembled_scans() < reference.size() && waited_ms < 20000;
       waited_ms += 10) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_EQ(live.assembled_scans(), reference.size());
  const auto scan = live.next();
  ASSERT_TRUE(scan.has_value());
  expect_same_scan(*scan, reference.back());
  EXPECT_FALSE(live.next().has_value());
  EXPECT_EQ(live.dropped_scans(), reference.size() - 1);
  EXPECT_EQ(live.stream()->stats().data_packets, sent.size());  // dropped after assembly, whole
}

TEST(LiveScanSource, ReadsPositionPacketsOnTheirOwnPort) {
  LiveSourceConfig config = loopback(2);
  config.receiver.position_port = 0;  // any free port
  LiveScanSource live(vlp16(), config);
  ASSERT_TRUE(live.position_port().has_value());
  ASSERT_NE(*live.position_port(), live.port());
  const std::string nmea = "$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6A";
  {
    UdpSender position({"127.0.0.1", *live.position_port()});
    std::vector<std::uint8_t> packet(velodyne::kPositionPacketBytes, 0);
    std::copy(nmea.begin(), nmea.end(), packet.begin() + 206);
    position.send(packet);
    position.send(std::vector<std::uint8_t>(100, 0));  // wrong size: counted, not read
  }
  send_paced(live.port(), payloads(packets()));
  while (live.next()) {
  }
  const auto& stats = live.stream()->stats();
  EXPECT_EQ(stats.position_packets, 1u);
  EXPECT_EQ(stats.bad_position_packets, 1u);
  ASSERT_TRUE(stats.last_position.has_value());
  EXPECT_EQ(stats.last_position->nmea, nmea);
  EXPECT_EQ(stats.data_packets, 400u);
}

TEST(LiveScanSource, StopEndsTheScansWithoutATimeout) {
  LiveSourceConfig config = loopback(2);
  config.receiver.idle_timeout_s = 0.0;  // wait forever
  LiveScanSource live(vlp16(), config);
  std::thread stopper([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    live.stop();
  });
  EXPECT_FALSE(live.next().has_value());
  stopper.join();
}

TEST(UdpEndpoint, ParsesListenAndSendAddresses) {
  EXPECT_EQ(parse_listen_endpoint("2368").port, 2368);
  EXPECT_EQ(parse_listen_endpoint("2368").host, "");
  const auto bound = parse_listen_endpoint("127.0.0.1:0");
  EXPECT_EQ(bound.host, "127.0.0.1");
  EXPECT_EQ(bound.port, 0);
  EXPECT_EQ(parse_send_endpoint("localhost:9000", "--to").port, 9000);
}

TEST(UdpEndpoint, BadTextIsAnErrorNamingTheFlagAndText) {
  try {
    parse_listen_endpoint("127.0.0.1:99999", "--udp");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "--udp");
    EXPECT_NE(std::string(e.what()).find("99999"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_listen_endpoint("port", "--udp"), InputError);
  EXPECT_THROW(parse_send_endpoint("9000", "--pose-udp"), InputError);         // no host
  EXPECT_THROW(parse_send_endpoint("127.0.0.1:0", "--pose-udp"), InputError);  // port 0
  EXPECT_THROW(parse_send_endpoint("no such host.invalid:9", "--to"), InputError);
}

TEST(UdpReceiver, AnAddressNotOfThisHostCannotBeBound) {
  try {
    UdpReceiverConfig config;
    config.listen = {"192.0.2.1", 0};  // TEST-NET-1: not an address of this host
    UdpReceiver receiver(config);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "udp://192.0.2.1:0");
    EXPECT_EQ(e.place(), "bind");
  }
}

}  // namespace
}  // namespace conicloc::io
