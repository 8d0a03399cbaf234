#pragma once
// Reads ROS 2 messages in CDR (OMG XCDR1 plain encoding, as rmw/Fast-CDR write them): a 4-byte
// encapsulation header (0x00 0x01 little-endian, 0x00 0x00 big-endian; options ignored), then the
// fields, each primitive aligned to its size relative to the first byte after the header. Strings
// are a uint32 length counting the terminating NUL, the bytes and the NUL. A read past the end or a
// malformed string throws CdrError naming the offset (from the start of the message).
//
// Example:
//   CdrReader cdr(message);
//   const std::int32_t sec = cdr.i32();
//   const std::string frame = cdr.string();

#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>

namespace conicloc::io {

class CdrError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class CdrReader {
 public:
  /// Reads the encapsulation header; throws CdrError for an unknown or cut one.
  explicit CdrReader(std::span<const std::uint8_t> message);

  std::uint8_t u8();
  std::uint32_t u32();
  std::int32_t i32() { return static_cast<std::int32_t>(u32()); }
  std::string string();
  /// `count` bytes of a fixed-size uint8 array (no length prefix, no alignment).
  std::span<const std::uint8_t> fixed_bytes(std::size_t count);
  /// Offset of the next byte from the start of the message (encapsulation header included).
  std::size_t offset() const { return offset_; }
  bool little_endian() const { return little_endian_; }

 private:
  void align(std::size_t size);
  std::span<const std::uint8_t> take(std::size_t count);

  std::span<const std::uint8_t> message_;
  std::size_t offset_ = 0;
  bool little_endian_ = true;
};

}  // namespace conicloc::io
