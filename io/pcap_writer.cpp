#include "io/pcap_writer.hpp"

#include <cmath>

#include "io/input_error.hpp"

namespace conicloc::io {
namespace {

constexpr std::size_t kEthernetHeaderBytes = 14;
constexpr std::size_t kIpv4HeaderBytes = 20;
constexpr std::size_t kUdpHeaderBytes = 8;
constexpr std::uint32_t kSnapLength = 65535;
constexpr std::uint32_t kLinkTypeEthernet = 1;

void put_be16(std::uint8_t* p, std::uint16_t v) {
  p[0] = static_cast<std::uint8_t>(v >> 8);
  p[1] = static_cast<std::uint8_t>(v & 0xFF);
}

// pcap headers are written little-endian explicitly (the magic tells readers the byte order).
void append_le32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>((v >> (8 * i)) & 0xFF));
}
void append_le16(std::vector<std::uint8_t>& out, std::uint16_t v) {
  out.push_back(static_cast<std::uint8_t>(v & 0xFF));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
}

std::uint16_t fold(std::uint32_t sum) {
  while (sum >> 16) sum = (sum & 0xFFFF) + (sum >> 16);
  return static_cast<std::uint16_t>(sum);
}

}  // namespace

std::uint32_t ones_complement_sum(std::span<const std::uint8_t> bytes, std::uint32_t sum) {
  std::size_t i = 0;
  for (; i + 1 < bytes.size(); i += 2)
    sum += static_cast<std::uint32_t>(bytes[i] << 8 | bytes[i + 1]);
  if (i < bytes.size()) sum += static_cast<std::uint32_t>(bytes[i] << 8);  // odd byte, zero-padded
  return fold(sum);
}

std::vector<std::uint8_t> make_udp_frame(std::span<const std::uint8_t> payload,
                                         const UdpEndpoints& endpoints, std::uint16_t ip_id) {
  const std::size_t udp_length = kUdpHeaderBytes + payload.size();
  const std::size_t ip_length = kIpv4HeaderBytes + udp_length;
  std::vector<std::uint8_t> frame(kEthernetHeaderBytes + ip_length, 0);
  std::uint8_t* eth = frame.data();
  std::copy(endpoints.dst_mac.begin(), endpoints.dst_mac.end(), eth);
  std::copy(endpoints.src_mac.begin(), endpoints.src_mac.end(), eth + 6);
  put_be16(eth + 12, 0x0800);  // EtherType IPv4

  std::uint8_t* ip = eth + kEthernetHeaderBytes;
  ip[0] = 0x45;  // version 4, IHL 5 words
  put_be16(ip + 2, static_cast<std::uint16_t>(ip_length));
  put_be16(ip + 4, ip_id);
  put_be16(ip + 6, 0x4000);  // don't fragment
  ip[8] = 64;                // TTL
  ip[9] = 17;                // UDP
  std::copy(endpoints.src_ip.begin(), endpoints.src_ip.end(), ip + 12);
  std::copy(endpoints.dst_ip.begin(), endpoints.dst_ip.end(), ip + 16);
  put_be16(ip + 10, static_cast<std::uint16_t>(
                        ~ones_complement_sum(std::span(ip, kIpv4HeaderBytes)) & 0xFFFF));

  std::uint8_t* udp = ip + kIpv4HeaderBytes;
  put_be16(udp, endpoints.src_port);
  put_be16(udp + 2, endpoints.dst_port);
  put_be16(udp + 4, static_cast<std::uint16_t>(udp_length));
  std::copy(payload.begin(), payload.end(), udp + kUdpHeaderBytes);
  // UDP checksum over the pseudo-header (addresses, protocol, length), header and data (RFC 768).
  std::uint32_t sum = ones_complement_sum(std::span(ip + 12, 8));
  sum += 17 + static_cast<std::uint32_t>(udp_length);
  sum = ones_complement_sum(std::span(udp, udp_length), sum);
  std::uint16_t checksum = static_cast<std::uint16_t>(~fold(sum) & 0xFFFF);
  if (checksum == 0) checksum = 0xFFFF;  // 0 means "no checksum" in UDP over IPv4
  put_be16(udp + 6, checksum);
  return frame;
}

PcapWriter::PcapWriter(const std::string& path)
    : path_(path), out_(path, std::ios::binary | std::ios::trunc) {
  if (!out_) throw InputError(path, "", "cannot create pcap file");
  std::vector<std::uint8_t> header;
  append_le32(header, 0xA1B2C3D4);  // microsecond-resolution pcap
  append_le16(header, 2);
  append_le16(header, 4);
  append_le32(header, 0);  // thiszone
  append_le32(header, 0);  // sigfigs
  append_le32(header, kSnapLength);
  append_le32(header, kLinkTypeEthernet);
  out_.write(reinterpret_cast<const char*>(header.data()),
             static_cast<std::streamsize>(header.size()));
}

PcapWriter::~PcapWriter() {
  if (out_.is_open()) out_.close();
}

void PcapWriter::write_udp(std::span<const std::uint8_t> payload, double utc_time_s,
                           const UdpEndpoints& endpoints) {
  const auto frame = make_udp_frame(payload, endpoints, static_cast<std::uint16_t>(packets_));
  write_frame(frame, utc_time_s);
}

void PcapWriter::write_frame(std::span<const std::uint8_t> frame, double utc_time_s) {
  const auto total_us = static_cast<std::int64_t>(std::llround(utc_time_s * 1e6));
  const auto seconds = static_cast<std::uint32_t>(total_us / 1'000'000);
  const auto micros = static_cast<std::uint32_t>(total_us % 1'000'000);
  const auto length = static_cast<std::uint32_t>(frame.size());
  std::vector<std::uint8_t> record;
  record.reserve(16);
  append_le32(record, seconds);
  append_le32(record, micros);
  append_le32(record, std::min(length, kSnapLength));
  append_le32(record, length);
  out_.write(reinterpret_cast<const char*>(record.data()), 16);
  out_.write(reinterpret_cast<const char*>(frame.data()),
             static_cast<std::streamsize>(std::min(length, kSnapLength)));
  if (!out_) throw InputError(path_, "packet " + std::to_string(packets_), "write failed");
  ++packets_;
}

void PcapWriter::close() {
  if (!out_.is_open()) return;
  out_.flush();
  const bool ok = static_cast<bool>(out_);
  out_.close();
  if (!ok) throw InputError(path_, "", "could not finish writing the pcap file");
}

}  // namespace conicloc::io
