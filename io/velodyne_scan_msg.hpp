#pragma once
// velodyne_msgs/VelodyneScan, the message the ROS Velodyne driver records: a std_msgs/Header and
// the raw packets of one rotation, each with its receive stamp and its 1206 bytes.
//   ROS 1 (velodyne_msgs/VelodyneScan):     uint32 seq, time stamp {uint32 sec, uint32 nsec},
//       string frame_id (uint32 length, no NUL), uint32 count, count × {time, uint8[1206]}.
//   ROS 2 (velodyne_msgs/msg/VelodyneScan): CDR; Time stamp {int32 sec, uint32 nanosec}, string
//       frame_id, sequence<VelodynePacket> (uint32 count), each {Time, uint8[1206]} (a fixed array:
//       no length prefix, no alignment).
// A message that does not hold what it says throws MessageError naming the byte offset.

#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace conicloc::io {

class MessageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// How a bag serialised its messages.
enum class MessageEncoding { Ros1, Cdr };

struct VelodynePacketView {
  double stamp_s = 0.0;                ///< ROS time of the packet (seconds since the epoch)
  std::span<const std::uint8_t> data;  ///< 1206 bytes, valid as long as the message buffer
};

struct VelodyneScanView {
  double stamp_s = 0.0;
  std::string frame_id;
  std::vector<VelodynePacketView> packets;
};

inline constexpr std::string_view kVelodyneScanRos1Type = "velodyne_msgs/VelodyneScan";
inline constexpr std::string_view kVelodyneScanRos2Type = "velodyne_msgs/msg/VelodyneScan";
inline constexpr std::size_t kVelodynePacketBytes = 1206;

/// True for the ROS 1 and ROS 2 names of the type.
bool is_velodyne_scan_type(std::string_view type);

/// Decodes one VelodyneScan message. Throws MessageError when it is cut or malformed.
VelodyneScanView decode_velodyne_scan(std::span<const std::uint8_t> message,
                                      MessageEncoding encoding);

}  // namespace conicloc::io
