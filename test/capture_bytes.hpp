#pragma once
// A classic pcap file as bytes, split into records, so tests can corrupt, cut, interleave and
// re-wrap (as pcapng) a capture the simulator wrote. Little-endian files only (what PcapWriter
// writes). Record layout: 16-byte header (ts_sec, ts_frac, caplen, len) + frame; a Velodyne frame
// is Ethernet (14) + IPv4 (20) + UDP (8) + payload.

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <vector>

namespace conicloc::test {

using Bytes = std::vector<std::uint8_t>;

inline constexpr std::size_t kPcapFileHeaderBytes = 24;
inline constexpr std::size_t kPcapRecordHeaderBytes = 16;
inline constexpr std::size_t kUdpPayloadOffset = 14 + 20 + 8;

inline std::uint32_t le32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
         static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}

inline void put_le32(Bytes& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

inline void put_le16(Bytes& out, std::uint16_t v) {
  out.push_back(static_cast<std::uint8_t>(v));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
}

inline Bytes read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void write_bytes(const std::filesystem::path& path, const Bytes& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

struct PcapRecord {
  std::uint32_t ts_sec = 0, ts_frac = 0;  ///< fraction in the file's unit (µs or ns)
  Bytes frame;
};

struct PcapFile {
  Bytes file_header;  ///< 24 bytes
  std::vector<PcapRecord> records;

  static PcapFile parse(const Bytes& bytes) {
    PcapFile file;
    if (bytes.size() < kPcapFileHeaderBytes) throw std::runtime_error("no pcap file header");
    file.file_header.assign(bytes.begin(), bytes.begin() + kPcapFileHeaderBytes);
    std::size_t at = kPcapFileHeaderBytes;
    while (at + kPcapRecordHeaderBytes <= bytes.size()) {
      PcapRecord record;
      record.ts_sec = le32(&bytes[at]);
      record.ts_frac = le32(&bytes[at + 4]);
      const std::size_t caplen = le32(&bytes[at + 8]);
      at += kPcapRecordHeaderBytes;
      if (at + caplen > bytes.size()) throw std::runtime_error("cut record");
      record.frame.assign(bytes.begin() + static_cast<long>(at),
                          bytes.begin() + static_cast<long>(at + caplen));
      at += caplen;
      file.records.push_back(std::move(record));
    }
    return file;
  }

  Bytes serialize() const {
    Bytes out = file_header;
    for (const auto& r : records) {
      put_le32(out, r.ts_sec);
      put_le32(out, r.ts_frac);
      put_le32(out, static_cast<std::uint32_t>(r.frame.size()));
      put_le32(out, static_cast<std::uint32_t>(r.frame.size()));
      out.insert(out.end(), r.frame.begin(), r.frame.end());
    }
    return out;
  }

  /// Byte offset of record `index` (0-based) in serialize().
  std::size_t record_offset(std::size_t index) const {
    std::size_t at = kPcapFileHeaderBytes;
    for (std::size_t i = 0; i < index; ++i) at += kPcapRecordHeaderBytes + records[i].frame.size();
    return at;
  }
};

/// An Ethernet + IPv4 frame (no checksums: the reader does not check them). `protocol` 17 = UDP;
/// for UDP the 8-byte header is written before `body`.
inline Bytes ipv4_frame(std::uint8_t protocol, std::uint16_t dst_port, const Bytes& body,
                        std::uint16_t fragment_field = 0x4000) {
  Bytes f(12, 0x02);  // MAC addresses
  f.push_back(0x08);
  f.push_back(0x00);
  const std::size_t l4 = body.size() + (protocol == 17 ? 8 : 0);
  const auto total = static_cast<std::uint16_t>(20 + l4);
  const Bytes ip = {0x45,
                    0,
                    static_cast<std::uint8_t>(total >> 8),
                    static_cast<std::uint8_t>(total),
                    0,
                    0,
                    static_cast<std::uint8_t>(fragment_field >> 8),
                    static_cast<std::uint8_t>(fragment_field),
                    64,
                    protocol,
                    0,
                    0,
                    192,
                    168,
                    1,
                    201,
                    255,
                    255,
                    255,
                    255};
  f.insert(f.end(), ip.begin(), ip.end());
  if (protocol == 17) {
    const auto udp_length = static_cast<std::uint16_t>(l4);
    const Bytes udp = {0x09,
                       0x40,
                       static_cast<std::uint8_t>(dst_port >> 8),
                       static_cast<std::uint8_t>(dst_port),
                       static_cast<std::uint8_t>(udp_length >> 8),
                       static_cast<std::uint8_t>(udp_length),
                       0,
                       0};
    f.insert(f.end(), udp.begin(), udp.end());
  }
  f.insert(f.end(), body.begin(), body.end());
  return f;
}

/// The records of a classic pcap as a pcapng section (SHB, one Ethernet IDB, one EPB per record,
/// µs time stamps); `extra_every` > 0 puts `extra_block` after every that many packets.
inline Bytes to_pcapng(const PcapFile& file, std::size_t extra_every, const Bytes& extra_block) {
  const bool nanoseconds = le32(file.file_header.data()) == 0xA1B23C4D;
  Bytes out;
  auto block = [&](std::uint32_t type, const Bytes& body) {
    const auto length = static_cast<std::uint32_t>(12 + body.size());
    put_le32(out, type);
    put_le32(out, length);
    out.insert(out.end(), body.begin(), body.end());
    put_le32(out, length);
  };
  Bytes shb;
  put_le32(shb, 0x1A2B3C4D);  // byte-order magic
  put_le16(shb, 1);
  put_le16(shb, 0);
  for (int i = 0; i < 8; ++i) shb.push_back(0xFF);  // section length unknown
  block(0x0A0D0D0A, shb);
  Bytes idb;
  put_le16(idb, 1);  // LINKTYPE_ETHERNET
  put_le16(idb, 0);
  put_le32(idb, 65535);
  block(1, idb);
  for (std::size_t i = 0; i < file.records.size(); ++i) {
    const auto& r = file.records[i];
    const std::uint64_t us =
        std::uint64_t{r.ts_sec} * 1000000u + (nanoseconds ? r.ts_frac / 1000u : r.ts_frac);
    Bytes epb;
    put_le32(epb, 0);  // interface
    put_le32(epb, static_cast<std::uint32_t>(us >> 32));
    put_le32(epb, static_cast<std::uint32_t>(us));
    put_le32(epb, static_cast<std::uint32_t>(r.frame.size()));
    put_le32(epb, static_cast<std::uint32_t>(r.frame.size()));
    epb.insert(epb.end(), r.frame.begin(), r.frame.end());
    while (epb.size() % 4) epb.push_back(0);
    block(6, epb);
    if (extra_every && (i + 1) % extra_every == 0)
      out.insert(out.end(), extra_block.begin(), extra_block.end());
  }
  return out;
}

}  // namespace conicloc::test
