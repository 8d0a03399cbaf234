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

#include "io/capture_source.hpp"

namespace conicloc::io {

class PcapReader : public CaptureSource {
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

  const CaptureCounts& counts() const override { return counts_; }
  std::string format() const override { return pcapng_ ? "pcapng" : "pcap"; }
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
