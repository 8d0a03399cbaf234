#include "io/rosbag1_header.hpp"

#include <algorithm>

#include "io/byte_cursor.hpp"

namespace conicloc::io {

Rosbag1Header::Rosbag1Header(std::span<const std::uint8_t> bytes) {
  ByteCursor cursor(bytes);
  while (!cursor.at_end()) {
    const std::size_t start = cursor.offset();
    std::span<const std::uint8_t> field;
    try {
      field = cursor.bytes(cursor.u32());
    } catch (const TruncatedBytes& e) {
      throw HeaderError("header field at byte " + std::to_string(start) + " cut short (" +
                        e.what() + ")");
    }
    const auto equals = std::find(field.begin(), field.end(), '=');
    if (equals == field.end()) {
      throw HeaderError("header field at byte " + std::to_string(start) + " has no '='");
    }
    const auto name_bytes = static_cast<std::size_t>(equals - field.begin());
    fields_[std::string(field.begin(), equals)] = field.subspan(name_bytes + 1);
  }
}

std::string Rosbag1Header::text(const std::string& name) const {
  const auto field = fields_.find(name);
  if (field == fields_.end()) throw HeaderError("header has no field '" + name + "'");
  return {field->second.begin(), field->second.end()};
}

std::uint64_t Rosbag1Header::integer(const std::string& name, std::size_t size) const {
  const auto field = fields_.find(name);
  if (field == fields_.end()) throw HeaderError("header has no field '" + name + "'");
  if (field->second.size() != size) {
    throw HeaderError("header field '" + name + "' has " + std::to_string(field->second.size()) +
                      " bytes, expected " + std::to_string(size));
  }
  std::uint64_t value = 0;
  for (std::size_t i = size; i-- > 0;) value = value << 8 | field->second[i];
  return value;
}

std::uint8_t Rosbag1Header::u8(const std::string& name) const {
  return static_cast<std::uint8_t>(integer(name, 1));
}
std::uint32_t Rosbag1Header::u32(const std::string& name) const {
  return static_cast<std::uint32_t>(integer(name, 4));
}
std::uint64_t Rosbag1Header::u64(const std::string& name) const {
  return integer(name, 8);
}

std::optional<std::uint8_t> Rosbag1Header::op() const {
  if (!has("op")) return std::nullopt;
  return u8("op");
}

}  // namespace conicloc::io
