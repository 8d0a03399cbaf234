// The reader understands the captures people actually have: pcap (µs and ns) and pcapng; Ethernet
// (with VLAN tags), Linux cooked SLL and SLL2, raw IP; unsupported link types are an InputError.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/input_error.hpp"
#include "io/pcap_reader.hpp"
#include "io/pcap_writer.hpp"
#include "test/temp_path.hpp"

namespace conicloc::io {
namespace {

using Bytes = std::vector<std::uint8_t>;

void put16(Bytes& b, std::uint16_t v) {
  b.push_back(static_cast<std::uint8_t>(v));
  b.push_back(static_cast<std::uint8_t>(v >> 8));
}
void put32(Bytes& b, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

Bytes payload() {
  Bytes p(1206);
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = static_cast<std::uint8_t>(i);
  return p;
}

Bytes ip_packet() {
  const Bytes frame = make_udp_frame(payload(), UdpEndpoints{});
  return Bytes(frame.begin() + 14, frame.end());
}

std::string save(const std::string& name, const Bytes& bytes) {
  const std::string path =
      conicloc::test::unique_temp_path("link_" + name).string();
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
  return path;
}

std::string classic(const std::string& name, std::uint32_t link_type, const Bytes& frame,
                    std::uint32_t magic = 0xA1B2C3D4, std::uint32_t fraction = 250000) {
  Bytes b;
  put32(b, magic);
  put16(b, 2);
  put16(b, 4);
  put32(b, 0);
  put32(b, 0);
  put32(b, 65535);
  put32(b, link_type);
  put32(b, 1700000000);
  put32(b, fraction);
  put32(b, static_cast<std::uint32_t>(frame.size()));
  put32(b, static_cast<std::uint32_t>(frame.size()));
  b.insert(b.end(), frame.begin(), frame.end());
  return save(name, b);
}

void expect_one_datagram(const std::string& path, double time_s = 1700000000.25) {
  PcapReader reader(path, {2368});
  const auto datagram = reader.next();
  ASSERT_TRUE(datagram.has_value()) << reader.link_type_name();
  EXPECT_EQ(datagram->dst_port, 2368);
  EXPECT_NEAR(datagram->capture_time_s, time_s, 1e-6);
  const Bytes expected = payload();
  ASSERT_EQ(datagram->payload.size(), expected.size());
  EXPECT_TRUE(std::equal(expected.begin(), expected.end(), datagram->payload.begin()));
  EXPECT_FALSE(reader.next().has_value());
  std::filesystem::remove(path);
}

TEST(PcapLinkTypes, Ethernet) {
  expect_one_datagram(classic("eth.pcap", 1, make_udp_frame(payload(), UdpEndpoints{})));
}

TEST(PcapLinkTypes, EthernetWithVlanTag) {
  Bytes frame = make_udp_frame(payload(), UdpEndpoints{});
  const Bytes tag = {0x81, 0x00, 0x00, 0x05};
  frame.insert(frame.begin() + 12, tag.begin(), tag.end());
  expect_one_datagram(classic("vlan.pcap", 1, frame));
}

TEST(PcapLinkTypes, NanosecondPcap) {
  expect_one_datagram(
      classic("ns.pcap", 1, make_udp_frame(payload(), UdpEndpoints{}), 0xA1B23C4D, 250000123),
      1700000000.250000123);
}

TEST(PcapLinkTypes, LinuxCookedSll) {
  Bytes frame = {0, 1, 0, 1, 0, 6, 0x60, 0x76, 0x88, 0, 0, 1, 0, 0, 0x08, 0x00};
  const Bytes ip = ip_packet();
  frame.insert(frame.end(), ip.begin(), ip.end());
  expect_one_datagram(classic("sll.pcap", 113, frame));
}

TEST(PcapLinkTypes, LinuxCookedSll2) {
  Bytes frame = {0x08, 0x00, 0, 0, 0, 0, 0, 2, 0, 1, 1, 6, 0x60, 0x76, 0x88, 0, 0, 1, 0, 0};
  const Bytes ip = ip_packet();
  frame.insert(frame.end(), ip.begin(), ip.end());
  expect_one_datagram(classic("sll2.pcap", 276, frame));
}

TEST(PcapLinkTypes, RawIp) {
  expect_one_datagram(classic("raw.pcap", 101, ip_packet()));
}

TEST(PcapLinkTypes, Pcapng) {
  Bytes b;
  // Section header block.
  put32(b, 0x0A0D0D0A);
  put32(b, 28);
  put32(b, 0x1A2B3C4D);
  put16(b, 1);
  put16(b, 0);
  put32(b, 0xFFFFFFFF);
  put32(b, 0xFFFFFFFF);
  put32(b, 28);
  // Interface description block: Ethernet, default µs resolution.
  put32(b, 1);
  put32(b, 20);
  put16(b, 1);
  put16(b, 0);
  put32(b, 65535);
  put32(b, 20);
  // Enhanced packet block.
  const Bytes frame = make_udp_frame(payload(), UdpEndpoints{});
  const std::size_t padded = (frame.size() + 3) / 4 * 4;
  const auto length = static_cast<std::uint32_t>(32 + padded);
  const std::uint64_t stamp_us = 1700000000ull * 1000000ull + 250000ull;
  put32(b, 6);
  put32(b, length);
  put32(b, 0);
  put32(b, static_cast<std::uint32_t>(stamp_us >> 32));
  put32(b, static_cast<std::uint32_t>(stamp_us & 0xFFFFFFFF));
  put32(b, static_cast<std::uint32_t>(frame.size()));
  put32(b, static_cast<std::uint32_t>(frame.size()));
  b.insert(b.end(), frame.begin(), frame.end());
  b.resize(b.size() + padded - frame.size(), 0);
  put32(b, length);
  expect_one_datagram(save("ng.pcapng", b));
}

TEST(PcapLinkTypes, UnsupportedLinkTypeIsAnInputError) {
  const std::string path = classic("usb.pcap", 189, Bytes(64, 0));  // LINKTYPE_USB_LINUX
  EXPECT_THROW(PcapReader reader(path), InputError);
  std::filesystem::remove(path);
}

TEST(PcapLinkTypes, NonUdpAndForeignPortsAreCountedNotDelivered) {
  Bytes tcp = make_udp_frame(payload(), UdpEndpoints{});
  tcp[14 + 9] = 6;  // protocol TCP
  UdpEndpoints other;
  other.dst_port = 5353;
  const std::string path = classic("tcp.pcap", 1, tcp);
  PcapReader reader(path, {2368});
  EXPECT_FALSE(reader.next().has_value());
  EXPECT_EQ(reader.counts().not_ipv4_udp, 1u);
  std::filesystem::remove(path);
  const std::string path2 = classic("mdns.pcap", 1, make_udp_frame(payload(), other));
  PcapReader reader2(path2, {2368});
  EXPECT_FALSE(reader2.next().has_value());
  EXPECT_EQ(reader2.counts().foreign_port, 1u);
  std::filesystem::remove(path2);
}

}  // namespace
}  // namespace conicloc::io
