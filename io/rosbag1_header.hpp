#pragma once
// The record header of ROS 1 bags (wiki.ros.org/Bags/Format/2.0), also the form of a connection's
// header: a sequence of fields, each a uint32 length and then "name=value", the value raw bytes
// (little-endian integers or text). Malformed headers throw HeaderError naming the byte offset
// within the header.

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>

namespace conicloc::io {

class HeaderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Rosbag1Header {
 public:
  /// Parses every field; throws HeaderError when a field runs past the end or has no '='.
  explicit Rosbag1Header(std::span<const std::uint8_t> bytes);

  bool has(const std::string& name) const { return fields_.count(name) != 0; }
  /// The field as text / as a little-endian integer; HeaderError when absent or of another size.
  std::string text(const std::string& name) const;
  std::uint8_t u8(const std::string& name) const;
  std::uint32_t u32(const std::string& name) const;
  std::uint64_t u64(const std::string& name) const;
  /// The record's "op" field, nullopt without one.
  std::optional<std::uint8_t> op() const;

 private:
  std::uint64_t integer(const std::string& name, std::size_t size) const;

  std::map<std::string, std::span<const std::uint8_t>> fields_;
};

}  // namespace conicloc::io
