#pragma once
// Decompresses the chunks of bag files with Debian's libraries: zstd frames (libzstd), LZ4 frames
// (liblz4's LZ4F API: MCAP "lz4" and ROS 1 "lz4" chunks, which roslz4 writes as LZ4 frames) and
// bzip2 streams (libbz2). The uncompressed size is known from the chunk's header; output of any
// other size is an error. Errors throw DecompressError with the library's reason.

#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace conicloc::io {

class DecompressError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class ChunkCompression { None, Zstd, Lz4Frame, Bzip2 };

/// Decompresses `compressed` into exactly `uncompressed_size` bytes.
std::vector<std::uint8_t> decompress_chunk(std::span<const std::uint8_t> compressed,
                                           ChunkCompression compression,
                                           std::uint64_t uncompressed_size);

}  // namespace conicloc::io
