#pragma once
// CRC-32 (IEEE 802.3, the zlib/PNG polynomial, reflected 0xEDB88320), the checksum of MCAP's
// chunks, data section and summary. Incremental: crc32(b, crc32(a)) == crc32(a + b).

#include <cstdint>
#include <span>

namespace conicloc::io {

/// CRC-32 of `bytes` continuing from `crc` (0 to start).
std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc = 0);

}  // namespace conicloc::io
