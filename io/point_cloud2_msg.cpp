#include "io/point_cloud2_msg.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <utility>

#include "io/byte_cursor.hpp"
#include "io/cdr_reader.hpp"

namespace conicloc::io {
namespace {

// The fewest bytes a PointField takes (name length, offset, datatype, count): a corrupt count must
// not reserve gigabytes.
constexpr std::size_t kMinimumRos1FieldBytes = 4 + 4 + 1 + 4;

PointFieldType field_type(std::uint8_t datatype, const std::string& name) {
  if (datatype < 1 || datatype > 8) {
    throw MessageError("PointCloud2 field '" + name + "' has unknown datatype " +
                       std::to_string(datatype));
  }
  return static_cast<PointFieldType>(datatype);
}

void check_count(std::uint32_t count, std::size_t remaining, const char* what) {
  if (count > remaining / kMinimumRos1FieldBytes) {
    throw MessageError(std::string("PointCloud2 ") + what + " count " + std::to_string(count) +
                       " exceeds the " + std::to_string(remaining) + " bytes left");
  }
}

// Every field inside a point, every point inside the data.
void check_layout(const PointCloud2View& cloud) {
  for (const auto& field : cloud.fields) {
    // A field of count 0 still names a value at its offset: that one must fit too.
    const std::uint64_t end =
        std::uint64_t{field.offset} +
        std::max<std::uint64_t>(field.count, 1) * point_field_size(field.datatype);
    if (end > cloud.point_step) {
      throw MessageError("PointCloud2 field '" + field.name + "' ends at byte " +
                         std::to_string(end) + ", beyond point_step " +
                         std::to_string(cloud.point_step));
    }
  }
  if (std::uint64_t{cloud.width} * cloud.point_step > cloud.row_step) {
    throw MessageError("PointCloud2 row_step " + std::to_string(cloud.row_step) + " < width " +
                       std::to_string(cloud.width) + " × point_step " +
                       std::to_string(cloud.point_step));
  }
  const std::uint64_t needed = std::uint64_t{cloud.height} * cloud.row_step;
  if (cloud.point_count() > 0 && needed > cloud.data.size()) {
    throw MessageError("PointCloud2 of " + std::to_string(cloud.height) + " × " +
                       std::to_string(cloud.width) + " points of " +
                       std::to_string(cloud.point_step) + " bytes needs " + std::to_string(needed) +
                       " bytes of data, has " + std::to_string(cloud.data.size()));
  }
}

PointCloud2View decode_ros1(std::span<const std::uint8_t> message) {
  ByteCursor cursor(message);
  PointCloud2View cloud;
  try {
    cursor.u32();  // seq
    const std::uint32_t sec = cursor.u32();
    cloud.stamp_s = static_cast<double>(sec) + static_cast<double>(cursor.u32()) * 1e-9;
    cloud.frame_id = cursor.prefixed_text();
    cloud.height = cursor.u32();
    cloud.width = cursor.u32();
    const std::uint32_t count = cursor.u32();
    check_count(count, cursor.remaining(), "field");
    for (std::uint32_t i = 0; i < count; ++i) {
      PointField field;
      field.name = cursor.prefixed_text();
      field.offset = cursor.u32();
      field.datatype = field_type(cursor.u8(), field.name);
      field.count = cursor.u32();
      cloud.fields.push_back(field);
    }
    cloud.is_bigendian = cursor.u8() != 0;
    cloud.point_step = cursor.u32();
    cloud.row_step = cursor.u32();
    cloud.data = cursor.bytes(cursor.u32());
    cloud.is_dense = cursor.u8() != 0;
  } catch (const TruncatedBytes& e) {
    throw MessageError(std::string("ROS 1 PointCloud2 cut short: ") + e.what());
  }
  if (!cursor.at_end()) {
    throw MessageError(std::to_string(cursor.remaining()) +
                       " bytes after the end of a ROS 1 PointCloud2");
  }
  return cloud;
}

PointCloud2View decode_cdr(std::span<const std::uint8_t> message) {
  PointCloud2View cloud;
  try {
    CdrReader cdr(message);
    const std::int32_t sec = cdr.i32();
    cloud.stamp_s = static_cast<double>(sec) + static_cast<double>(cdr.u32()) * 1e-9;
    cloud.frame_id = cdr.string();
    cloud.height = cdr.u32();
    cloud.width = cdr.u32();
    const std::uint32_t count = cdr.u32();
    check_count(count, message.size() - cdr.offset(), "field");
    for (std::uint32_t i = 0; i < count; ++i) {
      PointField field;
      field.name = cdr.string();
      field.offset = cdr.u32();
      field.datatype = field_type(cdr.u8(), field.name);
      field.count = cdr.u32();
      cloud.fields.push_back(field);
    }
    cloud.is_bigendian = cdr.u8() != 0;
    cloud.point_step = cdr.u32();
    cloud.row_step = cdr.u32();
    cloud.data = cdr.fixed_bytes(cdr.u32());
    cloud.is_dense = cdr.u8() != 0;
    if (message.size() - cdr.offset() >= 4) {
      throw MessageError(std::to_string(message.size() - cdr.offset()) +
                         " bytes after the end of a CDR PointCloud2");
    }
  } catch (const CdrError& e) {
    throw MessageError(std::string("CDR PointCloud2: ") + e.what());
  }
  return cloud;
}

template <class T>
double load(const std::uint8_t* bytes, bool swap) {
  std::uint8_t raw[sizeof(T)];
  std::memcpy(raw, bytes, sizeof(T));
  if (swap) {
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
  }
  T value;
  std::memcpy(&value, raw, sizeof(T));
  return static_cast<double>(value);
}

}  // namespace

bool is_point_cloud2_type(std::string_view type) {
  return type == kPointCloud2Ros1Type || type == kPointCloud2Ros2Type;
}

std::size_t point_field_size(PointFieldType type) {
  switch (type) {
    case PointFieldType::Int8:
    case PointFieldType::Uint8:
      return 1;
    case PointFieldType::Int16:
    case PointFieldType::Uint16:
      return 2;
    case PointFieldType::Int32:
    case PointFieldType::Uint32:
    case PointFieldType::Float32:
      return 4;
    case PointFieldType::Float64:
      return 8;
  }
  return 1;
}

const PointField* PointCloud2View::field(std::string_view name) const {
  for (const auto& f : fields) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

double PointCloud2View::value(const PointField& f, std::size_t index) const {
  const std::size_t row = index / width;
  const std::size_t column = index % width;
  const std::uint8_t* bytes = data.data() + row * row_step + column * point_step + f.offset;
  const bool swap = is_bigendian != (std::endian::native == std::endian::big);
  switch (f.datatype) {
    case PointFieldType::Int8:
      return load<std::int8_t>(bytes, false);
    case PointFieldType::Uint8:
      return load<std::uint8_t>(bytes, false);
    case PointFieldType::Int16:
      return load<std::int16_t>(bytes, swap);
    case PointFieldType::Uint16:
      return load<std::uint16_t>(bytes, swap);
    case PointFieldType::Int32:
      return load<std::int32_t>(bytes, swap);
    case PointFieldType::Uint32:
      return load<std::uint32_t>(bytes, swap);
    case PointFieldType::Float32:
      return load<float>(bytes, swap);
    case PointFieldType::Float64:
      return load<double>(bytes, swap);
  }
  return 0.0;
}

PointCloud2View decode_point_cloud2(std::span<const std::uint8_t> message,
                                    MessageEncoding encoding) {
  PointCloud2View cloud =
      encoding == MessageEncoding::Ros1 ? decode_ros1(message) : decode_cdr(message);
  check_layout(cloud);
  return cloud;
}

}  // namespace conicloc::io
