#pragma once
// sensor_msgs/PointCloud2, as the ROS Velodyne driver (velodyne_pointcloud) publishes one rotation:
// a std_msgs/Header, the cloud's shape and field layout, and the packed point bytes.
//   ROS 1 (sensor_msgs/PointCloud2):     header {uint32 seq, time stamp, string frame_id},
//       uint32 height, uint32 width, PointField[] fields {string name, uint32 offset,
//       uint8 datatype, uint32 count}, bool is_bigendian, uint32 point_step, uint32 row_step,
//       uint8[] data, bool is_dense. Little-endian, unaligned, strings without a NUL.
//   ROS 2 (sensor_msgs/msg/PointCloud2): the same fields in CDR (header {int32 sec, uint32
//       nanosec, string frame_id}), each primitive aligned to its size.
// A message that is cut, whose layout does not fit its bytes, or whose fields have an unknown
// datatype throws MessageError naming the place.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "io/velodyne_scan_msg.hpp"

namespace conicloc::io {

/// sensor_msgs/PointField datatypes.
enum class PointFieldType : std::uint8_t {
  Int8 = 1,
  Uint8 = 2,
  Int16 = 3,
  Uint16 = 4,
  Int32 = 5,
  Uint32 = 6,
  Float32 = 7,
  Float64 = 8
};

struct PointField {
  std::string name;
  std::uint32_t offset = 0;  ///< bytes from the start of a point
  PointFieldType datatype = PointFieldType::Float32;
  std::uint32_t count = 1;
};

struct PointCloud2View {
  double stamp_s = 0.0;  ///< header stamp, ROS time (seconds since the epoch)
  std::string frame_id;
  std::uint32_t height = 0;
  std::uint32_t width = 0;
  std::vector<PointField> fields;
  bool is_bigendian = false;
  std::uint32_t point_step = 0;
  std::uint32_t row_step = 0;
  std::span<const std::uint8_t> data;  ///< valid as long as the message buffer
  bool is_dense = false;

  std::size_t point_count() const { return std::size_t{height} * width; }
  /// The field named `name`, or nullptr.
  const PointField* field(std::string_view name) const;
  /// Point `index` (row-major) as a value of `field`, converted to double.
  double value(const PointField& field, std::size_t index) const;
};

inline constexpr std::string_view kPointCloud2Ros1Type = "sensor_msgs/PointCloud2";
inline constexpr std::string_view kPointCloud2Ros2Type = "sensor_msgs/msg/PointCloud2";

/// True for the ROS 1 and ROS 2 names of the type.
bool is_point_cloud2_type(std::string_view type);

/// Size in bytes of one value of `type`.
std::size_t point_field_size(PointFieldType type);

/// Decodes one PointCloud2 message and checks its layout (every field inside point_step, every
/// point inside data). Throws MessageError when it is cut or malformed.
PointCloud2View decode_point_cloud2(std::span<const std::uint8_t> message,
                                    MessageEncoding encoding);

}  // namespace conicloc::io
