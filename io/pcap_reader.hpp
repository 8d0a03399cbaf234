#pragma once
// Reads UDP datagrams from pcap and pcapng captures (libpcap), as recorded by tcpdump, Wireshark or
// VeloView. Link types: Ethernet (with 802.1Q/802.1ad tags), Linux cooked SLL and SLL2, raw IP,
// BSD loopback. IPv4 UDP only; datagrams whose destination port is not wanted are counted and
// skipped, as is everything else that cannot be a sensor packet, by reason. A file that is not a
// capture at all throws InputError; a record cut by the end of the file ends the read and is
// counted (every record before it is delivered).
//
// Example:
//   io::PcapReader reader("run.pcap", {2368, 8308});
//   while (auto datagram = reader.next()) {
//     if (datagram->dst_port == 2368) handle(datagram->payload, datagram->capture_time_s);
//   }
//   spdlog::info("{} records, {} foreign port", reader.counts().records,
//   reader.counts().foreign_port);

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "io/datagram_source.hpp"

namespace conicloc::io {

struct CaptureCounts {
  std::size_t records = 0;             ///< records read from the file (complete ones)
  std::size_t udp_datagrams = 0;       ///< delivered by next()
  std::size_t truncated_records = 0;   ///< the file ended (or broke) inside a record
  std::size_t snap_length_cut = 0;     ///< captured fewer bytes than the frame had
  std::size_t not_ipv4_udp = 0;        ///< ARP, IPv6, TCP, ICMP, IP fragments, other link payloads
  std::size_t malformed = 0;           ///< UDP length beyond the captured bytes, bad IHL
  std::size_t foreign_port = 0;        ///< UDP to a port not asked for
  std::size_t ip_length_mismatch = 0;  ///< kept: IPv4 total length disagrees, UDP datagram whole
  std::string stop_message;            ///< libpcap's message when reading stopped on an error
  /// Byte offset of the record where reading stopped (classic pcap; nullopt for pcapng).
  std::optional<std::uint64_t> stop_offset;
};

class PcapReader : public DatagramSource {
 public:
  /// Opens `path`. `ports`: wanted UDP destination ports (empty: all). Throws InputError when the
  /// file cannot be opened, is not a pcap/pcapng capture, or has an unsupported link type.
  explicit PcapReader(const std::string& path, std::vector<std::uint16_t> ports = {});
  ~PcapReader() override;
  PcapReader(const PcapReader&) = delete;
  PcapReader& operator=(const PcapReader&) = delete;

  /// The next wanted UDP datagram, or nullopt at the end of the capture.
  std::optional<UdpDatagram> next() override;
  std::string name() const override { return path_; }

  const CaptureCounts& counts() const { return counts_; }
  const std::string& path() const { return path_; }
  /// libpcap's name of the link type ("EN10MB", "LINUX_SLL2", ...).
  std::string link_type_name() const;

 private:
  struct Handle;
  std::optional<UdpDatagram> parse_frame(const std::uint8_t* data, std::size_t captured,
                                         std::size_t length, double time_s);

  std::string path_;
  std::vector<std::uint16_t> ports_;
  std::unique_ptr<Handle> handle_;
  int link_type_ = 0;
  bool pcapng_ = false;
  std::uint64_t next_record_offset_ = 24;  ///< classic pcap: after the 24-byte file header
  CaptureCounts counts_;
};

}  // namespace conicloc::io
