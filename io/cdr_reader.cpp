#include "io/cdr_reader.hpp"

#include <cstdio>

namespace conicloc::io {
namespace {

constexpr std::size_t kEncapsulationBytes = 4;

}  // namespace

CdrReader::CdrReader(std::span<const std::uint8_t> message) : message_(message) {
  if (message.size() < kEncapsulationBytes) {
    throw CdrError("message of " + std::to_string(message.size()) +
                   " bytes has no CDR encapsulation header");
  }
  // Representation identifier: CDR_BE 0x0000, CDR_LE 0x0001 (the options bytes are not used).
  if (message[0] != 0 || message[1] > 1) {
    char id[8];
    std::snprintf(id, sizeof id, "%02x%02x", message[0], message[1]);
    throw CdrError(std::string("unknown CDR encapsulation 0x") + id +
                   " (expected plain CDR, 0x0000 or 0x0001)");
  }
  little_endian_ = message[1] == 1;
  offset_ = kEncapsulationBytes;
}

void CdrReader::align(std::size_t size) {
  const std::size_t from_origin = offset_ - kEncapsulationBytes;
  const std::size_t padding = (size - from_origin % size) % size;
  take(padding);
}

std::span<const std::uint8_t> CdrReader::take(std::size_t count) {
  if (count > message_.size() - offset_) {
    throw CdrError("message ends at byte " + std::to_string(message_.size()) + ", needs " +
                   std::to_string(count) + " bytes at offset " + std::to_string(offset_));
  }
  const auto view = message_.subspan(offset_, count);
  offset_ += count;
  return view;
}

std::uint8_t CdrReader::u8() {
  return take(1)[0];
}

std::uint32_t CdrReader::u32() {
  align(4);
  const auto b = take(4);
  if (little_endian_) {
    return std::uint32_t{b[0]} | std::uint32_t{b[1]} << 8 | std::uint32_t{b[2]} << 16 |
           std::uint32_t{b[3]} << 24;
  }
  return std::uint32_t{b[3]} | std::uint32_t{b[2]} << 8 | std::uint32_t{b[1]} << 16 |
         std::uint32_t{b[0]} << 24;
}

std::string CdrReader::string() {
  const std::size_t start = offset_;
  const std::uint32_t length = u32();
  if (length == 0) return {};  // some writers encode "" as length 0 without the NUL
  const auto bytes = take(length);
  if (bytes.back() != 0) {
    throw CdrError("string at offset " + std::to_string(start) + " is not NUL-terminated");
  }
  return {bytes.begin(), bytes.end() - 1};
}

std::span<const std::uint8_t> CdrReader::fixed_bytes(std::size_t count) {
  return take(count);
}

}  // namespace conicloc::io
