#pragma once
// Bounds-checked little-endian reads from a byte buffer, for the bag formats (MCAP, ROS 1 bags).
// Reading past the end throws TruncatedBytes naming the offset; the caller turns it into an
// InputError that names the file and the record.

#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>

namespace conicloc::io {

class TruncatedBytes : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ByteCursor {
 public:
  explicit ByteCursor(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}

  std::size_t offset() const { return offset_; }
  std::size_t remaining() const { return bytes_.size() - offset_; }
  bool at_end() const { return offset_ == bytes_.size(); }

  std::uint8_t u8() { return take(1)[0]; }
  std::uint16_t u16() { return static_cast<std::uint16_t>(little_endian(take(2))); }
  std::uint32_t u32() { return static_cast<std::uint32_t>(little_endian(take(4))); }
  std::uint64_t u64() { return little_endian(take(8)); }
  /// The next `count` bytes (a view into the buffer).
  std::span<const std::uint8_t> bytes(std::uint64_t count) { return take(count); }
  std::string text(std::uint64_t count) {
    const auto view = take(count);
    return {view.begin(), view.end()};
  }
  /// MCAP's string and byte-array forms: a uint32 (or uint64) length, then the bytes.
  std::string prefixed_text() { return text(u32()); }
  void skip(std::uint64_t count) { take(count); }

 private:
  std::span<const std::uint8_t> take(std::uint64_t count) {
    if (count > remaining()) {
      throw TruncatedBytes("needs " + std::to_string(count) + " bytes at offset " +
                           std::to_string(offset_) + ", only " + std::to_string(remaining()) +
                           " left");
    }
    const auto view = bytes_.subspan(offset_, static_cast<std::size_t>(count));
    offset_ += static_cast<std::size_t>(count);
    return view;
  }
  static std::uint64_t little_endian(std::span<const std::uint8_t> bytes) {
    std::uint64_t value = 0;
    for (std::size_t i = bytes.size(); i-- > 0;) value = value << 8 | bytes[i];
    return value;
  }

  std::span<const std::uint8_t> bytes_;
  std::size_t offset_ = 0;
};

}  // namespace conicloc::io
