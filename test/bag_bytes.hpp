#pragma once
// Small bags built byte by byte for the reader tests: VelodyneScan messages in CDR and ROS 1
// serialisation, MCAP records and ROS 1 bag records, following the published format documents.
// The end-to-end tests use independent writers instead (test/bags/).

#include <cstdint>
#include <string>
#include <vector>

#include "test/capture_bytes.hpp"

namespace conicloc::test {

inline void put_le64(Bytes& out, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
inline void put_text(Bytes& out, const std::string& text) {
  out.insert(out.end(), text.begin(), text.end());
}
inline void append(Bytes& out, const Bytes& more) {
  out.insert(out.end(), more.begin(), more.end());
}

/// Packet i of the test messages: 1206 bytes of value (seed + i), stamped 100 s + i ms.
inline Bytes packet_bytes(int seed) {
  return Bytes(1206, static_cast<std::uint8_t>(seed));
}

/// CDR (little-endian) VelodyneScan of `count` packets.
inline Bytes cdr_velodyne_scan(int count, const std::string& frame_id = "velodyne") {
  Bytes out = {0x00, 0x01, 0x00, 0x00};
  const auto align4 = [&] {
    while ((out.size() - 4) % 4) out.push_back(0);
  };
  put_le32(out, 100);  // header.stamp.sec
  put_le32(out, 5);    // nanosec
  put_le32(out, static_cast<std::uint32_t>(frame_id.size() + 1));
  put_text(out, frame_id);
  out.push_back(0);
  align4();
  put_le32(out, static_cast<std::uint32_t>(count));
  for (int i = 0; i < count; ++i) {
    align4();
    put_le32(out, 100);
    put_le32(out, static_cast<std::uint32_t>(i) * 1000000);
    append(out, packet_bytes(i));
  }
  return out;
}

/// ROS 1 VelodyneScan of `count` packets.
inline Bytes ros1_velodyne_scan(int count) {
  Bytes out;
  put_le32(out, 7);    // seq
  put_le32(out, 100);  // stamp
  put_le32(out, 5);
  put_le32(out, 8);
  put_text(out, "velodyne");
  put_le32(out, static_cast<std::uint32_t>(count));
  for (int i = 0; i < count; ++i) {
    put_le32(out, 100);
    put_le32(out, static_cast<std::uint32_t>(i) * 1000000);
    append(out, packet_bytes(i));
  }
  return out;
}

// --- MCAP ---------------------------------------------------------------------------------------

inline Bytes mcap_record(std::uint8_t opcode, const Bytes& content) {
  Bytes out = {opcode};
  put_le64(out, content.size());
  append(out, content);
  return out;
}
inline void put_mcap_string(Bytes& out, const std::string& text) {
  put_le32(out, static_cast<std::uint32_t>(text.size()));
  put_text(out, text);
}
inline Bytes mcap_magic() {
  return {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
}
inline Bytes mcap_schema(std::uint16_t id, const std::string& name) {
  Bytes c;
  put_le16(c, id);
  put_mcap_string(c, name);
  put_mcap_string(c, "ros2msg");
  put_mcap_string(c, "");
  return mcap_record(0x03, c);
}
inline Bytes mcap_channel(std::uint16_t id, std::uint16_t schema, const std::string& topic,
                          const std::string& message_encoding = "cdr") {
  Bytes c;
  put_le16(c, id);
  put_le16(c, schema);
  put_mcap_string(c, topic);
  put_mcap_string(c, message_encoding);
  put_le32(c, 0);  // empty metadata map
  return mcap_record(0x04, c);
}
inline Bytes mcap_message(std::uint16_t channel, const Bytes& data) {
  Bytes c;
  put_le16(c, channel);
  put_le32(c, 0);
  put_le64(c, 1);
  put_le64(c, 1);
  append(c, data);
  return mcap_record(0x05, c);
}
inline Bytes mcap_chunk(const Bytes& records, const std::string& compression,
                        const Bytes& compressed) {
  Bytes c;
  put_le64(c, 0);
  put_le64(c, 0);
  put_le64(c, records.size());
  put_le32(c, 0);
  put_mcap_string(c, compression);
  put_le64(c, compressed.size());
  append(c, compressed);
  return mcap_record(0x06, c);
}
/// Footer without a summary, and the closing magic.
inline Bytes mcap_end() {
  Bytes c;
  put_le64(c, 0);
  put_le64(c, 0);
  put_le32(c, 0);
  Bytes out = mcap_record(0x02, c);
  append(out, mcap_magic());
  return out;
}

// --- ROS 1 bags ---------------------------------------------------------------------------------

/// A header field "name=value".
inline Bytes ros1_field(const std::string& name, const Bytes& value) {
  Bytes out;
  put_le32(out, static_cast<std::uint32_t>(name.size() + 1 + value.size()));
  put_text(out, name + "=");
  append(out, value);
  return out;
}
inline Bytes le32_bytes(std::uint32_t v) {
  Bytes out;
  put_le32(out, v);
  return out;
}
inline Bytes text_bytes(const std::string& text) {
  return Bytes(text.begin(), text.end());
}
inline Bytes ros1_record(const Bytes& header, const Bytes& data) {
  Bytes out;
  put_le32(out, static_cast<std::uint32_t>(header.size()));
  append(out, header);
  put_le32(out, static_cast<std::uint32_t>(data.size()));
  append(out, data);
  return out;
}
/// Version line and a bag header without an index.
inline Bytes ros1_start() {
  Bytes out = text_bytes("#ROSBAG V2.0\n");
  Bytes header = ros1_field("op", {0x03});
  Bytes zero8(8, 0);
  append(header, ros1_field("index_pos", zero8));
  append(header, ros1_field("conn_count", le32_bytes(1)));
  append(header, ros1_field("chunk_count", le32_bytes(0)));
  append(out, ros1_record(header, Bytes(16, ' ')));
  return out;
}
inline Bytes ros1_connection(std::uint32_t id, const std::string& topic, const std::string& type) {
  Bytes header = ros1_field("op", {0x07});
  append(header, ros1_field("conn", le32_bytes(id)));
  append(header, ros1_field("topic", text_bytes(topic)));
  Bytes data = ros1_field("topic", text_bytes(topic));
  append(data, ros1_field("type", text_bytes(type)));
  append(data, ros1_field("md5sum", text_bytes("*")));
  return ros1_record(header, data);
}
inline Bytes ros1_message(std::uint32_t connection, const Bytes& data) {
  Bytes header = ros1_field("op", {0x02});
  append(header, ros1_field("conn", le32_bytes(connection)));
  Bytes time;
  put_le32(time, 100);
  put_le32(time, 0);
  append(header, ros1_field("time", time));
  return ros1_record(header, data);
}
inline Bytes ros1_chunk(const std::string& compression, std::uint32_t size, const Bytes& data) {
  Bytes header = ros1_field("op", {0x05});
  append(header, ros1_field("compression", text_bytes(compression)));
  append(header, ros1_field("size", le32_bytes(size)));
  return ros1_record(header, data);
}

}  // namespace conicloc::test
