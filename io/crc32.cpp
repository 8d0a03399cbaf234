#include "io/crc32.hpp"

#include <array>

namespace conicloc::io {
namespace {

// One table entry per byte value: the remainder of its 8 shifts through the reflected polynomial.
constexpr std::array<std::uint32_t, 256> make_table() {
  std::array<std::uint32_t, 256> table{};
  for (std::uint32_t n = 0; n < 256; ++n) {
    std::uint32_t c = n;
    for (int k = 0; k < 8; ++k) c = (c & 1U) != 0 ? 0xEDB88320U ^ (c >> 1) : c >> 1;
    table[n] = c;
  }
  return table;
}

constexpr std::array<std::uint32_t, 256> kTable = make_table();

}  // namespace

std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc) {
  // The register starts and ends inverted, so the result of one call continues in the next.
  std::uint32_t c = ~crc;
  for (const std::uint8_t byte : bytes) c = kTable[(c ^ byte) & 0xFFU] ^ (c >> 8);
  return ~c;
}

}  // namespace conicloc::io
