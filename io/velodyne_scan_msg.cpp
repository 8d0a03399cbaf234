#include "io/velodyne_scan_msg.hpp"

#include "io/byte_cursor.hpp"
#include "io/cdr_reader.hpp"

namespace conicloc::io {
namespace {

double ros_time_s(std::int64_t sec, std::uint32_t nsec) {
  return static_cast<double>(sec) + static_cast<double>(nsec) * 1e-9;
}

// The packet count cannot exceed what the remaining bytes could hold: a corrupt count must not
// reserve gigabytes.
void check_count(const char* kind, std::uint32_t count, std::size_t remaining, std::size_t offset) {
  const std::size_t minimum_packet_bytes = 8 + kVelodynePacketBytes;
  if (count > remaining / minimum_packet_bytes) {
    throw MessageError(std::string(kind) + " VelodyneScan: packet count " + std::to_string(count) +
                       " at offset " + std::to_string(offset) + " exceeds the " +
                       std::to_string(remaining) + " bytes left");
  }
}

VelodyneScanView decode_ros1(std::span<const std::uint8_t> message) {
  ByteCursor cursor(message);
  VelodyneScanView scan;
  try {
    cursor.u32();  // seq
    const std::uint32_t sec = cursor.u32();
    scan.stamp_s = ros_time_s(sec, cursor.u32());
    scan.frame_id = cursor.prefixed_text();
    const std::size_t count_offset = cursor.offset();
    const std::uint32_t count = cursor.u32();
    check_count("ROS 1", count, cursor.remaining(), count_offset);
    scan.packets.reserve(count);
    for (std::uint32_t i = 0; i < count; ++i) {
      const std::uint32_t packet_sec = cursor.u32();
      const double stamp_s = ros_time_s(packet_sec, cursor.u32());
      scan.packets.push_back({stamp_s, cursor.bytes(kVelodynePacketBytes)});
    }
  } catch (const TruncatedBytes& e) {
    throw MessageError(std::string("ROS 1 VelodyneScan cut short: ") + e.what());
  }
  if (!cursor.at_end()) {
    throw MessageError(std::to_string(cursor.remaining()) +
                       " bytes after the last packet of a ROS 1 VelodyneScan");
  }
  return scan;
}

VelodyneScanView decode_cdr(std::span<const std::uint8_t> message) {
  VelodyneScanView scan;
  try {
    CdrReader cdr(message);
    const std::int32_t sec = cdr.i32();
    scan.stamp_s = ros_time_s(sec, cdr.u32());
    scan.frame_id = cdr.string();
    const std::uint32_t count = cdr.u32();
    check_count("CDR", count, message.size() - cdr.offset(), cdr.offset() - 4);
    scan.packets.reserve(count);
    for (std::uint32_t i = 0; i < count; ++i) {
      const std::int32_t packet_sec = cdr.i32();
      const double stamp_s = ros_time_s(packet_sec, cdr.u32());
      scan.packets.push_back({stamp_s, cdr.fixed_bytes(kVelodynePacketBytes)});
    }
    // Writers may pad the message to a multiple of 4 bytes; more than that is not this type.
    if (message.size() - cdr.offset() >= 4) {
      throw MessageError(std::to_string(message.size() - cdr.offset()) +
                         " bytes after the last packet of a CDR VelodyneScan");
    }
  } catch (const CdrError& e) {
    throw MessageError(std::string("CDR VelodyneScan: ") + e.what());
  }
  return scan;
}

}  // namespace

bool is_velodyne_scan_type(std::string_view type) {
  return type == kVelodyneScanRos1Type || type == kVelodyneScanRos2Type;
}

VelodyneScanView decode_velodyne_scan(std::span<const std::uint8_t> message,
                                      MessageEncoding encoding) {
  return encoding == MessageEncoding::Ros1 ? decode_ros1(message) : decode_cdr(message);
}

}  // namespace conicloc::io
