#include "io/pcap_reader.hpp"

#include <pcap/pcap.h>

#include <algorithm>
#include <cstdio>

#include "io/input_error.hpp"

namespace conicloc::io {
namespace {

std::uint16_t be16(const std::uint8_t* p) {
  return static_cast<std::uint16_t>(p[0] << 8 | p[1]);
}

constexpr std::uint16_t kEtherTypeIpv4 = 0x0800;
constexpr std::uint16_t kEtherTypeVlan = 0x8100;
constexpr std::uint16_t kEtherTypeQinQ = 0x88A8;
constexpr int kLinkTypeLinuxSll2 = 276;  // DLT_LINUX_SLL2 (absent from older pcap headers)
constexpr int kLinkTypeIpv4 = 228;       // DLT_IPV4

// Where the IPv4 header starts in a frame of `link_type`, or nullopt when the frame carries
// something else. Link-header layouts: tcpdump.org/linktypes.html.
std::optional<std::size_t> ipv4_offset(int link_type, const std::uint8_t* data, std::size_t size) {
  switch (link_type) {
    case DLT_EN10MB: {
      std::size_t offset = 12;
      if (size < offset + 2) return std::nullopt;
      std::uint16_t type = be16(data + offset);
      while ((type == kEtherTypeVlan || type == kEtherTypeQinQ) && size >= offset + 6) {
        offset += 4;
        type = be16(data + offset);
      }
      if (type != kEtherTypeIpv4) return std::nullopt;
      return offset + 2;
    }
    case DLT_LINUX_SLL:
      if (size < 16 || be16(data + 14) != kEtherTypeIpv4) return std::nullopt;
      return 16;
    case kLinkTypeLinuxSll2:
      if (size < 20 || be16(data) != kEtherTypeIpv4) return std::nullopt;
      return 20;
    case DLT_RAW:
    case kLinkTypeIpv4:
      return 0;
    case DLT_NULL:
    case DLT_LOOP: {
      // 4-byte address family in the capturing host's order (DLT_NULL) or network order (LOOP);
      // AF_INET is 2 everywhere.
      if (size < 4) return std::nullopt;
      const bool inet = (data[0] == 2 && data[1] == 0 && data[2] == 0 && data[3] == 0) ||
                        (data[0] == 0 && data[1] == 0 && data[2] == 0 && data[3] == 2);
      if (!inet) return std::nullopt;
      return 4;
    }
    default:
      return std::nullopt;
  }
}

bool supported_link_type(int link_type) {
  return link_type == DLT_EN10MB || link_type == DLT_LINUX_SLL || link_type == kLinkTypeLinuxSll2 ||
         link_type == DLT_RAW || link_type == kLinkTypeIpv4 || link_type == DLT_NULL ||
         link_type == DLT_LOOP;
}

}  // namespace

struct PcapReader::Handle {
  pcap_t* pcap = nullptr;
  ~Handle() {
    if (pcap) pcap_close(pcap);
  }
};

PcapReader::PcapReader(const std::string& path, std::vector<std::uint16_t> ports)
    : path_(path), ports_(std::move(ports)), handle_(std::make_unique<Handle>()) {
  char error[PCAP_ERRBUF_SIZE] = {};
  handle_->pcap =
      pcap_open_offline_with_tstamp_precision(path.c_str(), PCAP_TSTAMP_PRECISION_NANO, error);
  if (!handle_->pcap) {
    throw InputError(path, "file header",
                     std::string("not a readable pcap/pcapng capture (") + error + ")");
  }
  link_type_ = pcap_datalink(handle_->pcap);
  // libpcap does not say which of its two formats it opened; byte offsets need to know.
  if (FILE* file = std::fopen(path.c_str(), "rb")) {
    unsigned char magic[4] = {};
    pcapng_ = std::fread(magic, 1, 4, file) == 4 && magic[0] == 0x0A && magic[1] == 0x0D &&
              magic[2] == 0x0D && magic[3] == 0x0A;
    std::fclose(file);
  }
  if (!supported_link_type(link_type_)) {
    const char* name = pcap_datalink_val_to_name(link_type_);
    throw InputError(path, "file header",
                     "unsupported link type " + std::to_string(link_type_) + " (" +
                         (name ? name : "unknown") +
                         "); supported: Ethernet, Linux SLL/SLL2, raw IP, loopback");
  }
}

PcapReader::~PcapReader() = default;

std::string PcapReader::link_type_name() const {
  const char* name = pcap_datalink_val_to_name(link_type_);
  return name ? name : std::to_string(link_type_);
}

std::optional<UdpDatagram> PcapReader::next() {
  if (!handle_->pcap) return std::nullopt;
  for (;;) {
    pcap_pkthdr* header = nullptr;
    const u_char* data = nullptr;
    const int status = pcap_next_ex(handle_->pcap, &header, &data);
    if (status == PCAP_ERROR_BREAK) return std::nullopt;  // clean end of file
    if (status != 1) {
      // libpcap cannot resynchronise after a broken record: count it and stop here.
      ++counts_.truncated_records;
      counts_.stop_message = pcap_geterr(handle_->pcap);
      if (!pcapng_) counts_.stop_offset = next_record_offset_;
      pcap_close(handle_->pcap);
      handle_->pcap = nullptr;
      return std::nullopt;
    }
    ++counts_.records;
    next_record_offset_ += 16 + header->caplen;
    const double time_s = static_cast<double>(header->ts.tv_sec) + header->ts.tv_usec * 1e-9;
    if (auto datagram = parse_frame(data, header->caplen, header->len, time_s)) return datagram;
  }
}

std::optional<UdpDatagram> PcapReader::parse_frame(const std::uint8_t* data, std::size_t captured,
                                                   std::size_t length, double time_s) {
  if (captured < length) {
    ++counts_.snap_length_cut;
    return std::nullopt;
  }
  const auto ip_start = ipv4_offset(link_type_, data, captured);
  if (!ip_start || captured < *ip_start + 20 || (data[*ip_start] >> 4) != 4) {
    ++counts_.not_ipv4_udp;
    return std::nullopt;
  }
  const std::uint8_t* ip = data + *ip_start;
  const std::size_t available = captured - *ip_start;
  const std::size_t header_bytes = static_cast<std::size_t>(ip[0] & 0x0F) * 4;
  const std::size_t total = be16(ip + 2);
  const bool fragment = (be16(ip + 6) & 0x3FFF) != 0;  // MF flag or a fragment offset
  if (ip[9] != 17 || fragment) {
    ++counts_.not_ipv4_udp;
    return std::nullopt;
  }
  if (header_bytes < 20 || available < header_bytes + 8) {
    ++counts_.malformed;
    return std::nullopt;
  }
  const std::uint8_t* udp = ip + header_bytes;
  const std::size_t udp_length = be16(udp + 4);
  if (udp_length < 8 || header_bytes + udp_length > available) {
    ++counts_.malformed;
    return std::nullopt;
  }
  if (total < header_bytes + udp_length || total > available) {
    // VLP-16 firmware sends position packets with the IPv4 total length of a data packet; the
    // UDP datagram itself is complete, so it is kept (and counted).
    ++counts_.ip_length_mismatch;
  }
  UdpDatagram datagram;
  datagram.src_address = (std::uint32_t{be16(ip + 12)} << 16) | be16(ip + 14);
  datagram.src_port = be16(udp);
  datagram.dst_port = be16(udp + 2);
  if (!ports_.empty() &&
      std::find(ports_.begin(), ports_.end(), datagram.dst_port) == ports_.end()) {
    ++counts_.foreign_port;
    return std::nullopt;
  }
  datagram.payload = std::span<const std::uint8_t>(udp + 8, udp_length - 8);
  datagram.capture_time_s = time_s;
  datagram.record = counts_.records;
  ++counts_.udp_datagrams;
  return datagram;
}

}  // namespace conicloc::io
