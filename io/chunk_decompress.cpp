#include "io/chunk_decompress.hpp"

#include <bzlib.h>
#include <lz4frame.h>
#include <zstd.h>

#include <memory>

namespace conicloc::io {
namespace {

// A chunk is at most this large uncompressed: a corrupt size must not allocate the machine away.
constexpr std::uint64_t kMaxChunkBytes = std::uint64_t{4} << 30;

void check_size(std::size_t produced, std::uint64_t expected, const char* codec) {
  if (produced != expected) {
    throw DecompressError(std::string(codec) + " gave " + std::to_string(produced) +
                          " bytes, the chunk header says " + std::to_string(expected));
  }
}

std::vector<std::uint8_t> zstd(std::span<const std::uint8_t> in, std::uint64_t size) {
  std::vector<std::uint8_t> out(size);
  const std::size_t produced = ZSTD_decompress(out.data(), out.size(), in.data(), in.size());
  if (ZSTD_isError(produced)) {
    throw DecompressError(std::string("zstd: ") + ZSTD_getErrorName(produced));
  }
  check_size(produced, size, "zstd");
  return out;
}

std::vector<std::uint8_t> lz4_frame(std::span<const std::uint8_t> in, std::uint64_t size) {
  LZ4F_dctx* raw = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) {
    throw DecompressError("lz4: cannot create a decompression context");
  }
  const std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> context(
      raw, LZ4F_freeDecompressionContext);
  std::vector<std::uint8_t> out(size);
  std::size_t read = 0;
  std::size_t written = 0;
  for (;;) {
    std::size_t in_bytes = in.size() - read;
    std::size_t out_bytes = out.size() - written;
    const std::size_t hint =
        LZ4F_decompress(context.get(), out.data() + written, &out_bytes, in.data() + read,
                        &in_bytes, nullptr);
    if (LZ4F_isError(hint)) throw DecompressError(std::string("lz4: ") + LZ4F_getErrorName(hint));
    read += in_bytes;
    written += out_bytes;
    if (hint == 0) break;  // the frame is complete
    if (in_bytes == 0 && out_bytes == 0) {
      throw DecompressError(read == in.size() ? "lz4: the frame is cut short"
                                              : "lz4: more data than the chunk header says");
    }
  }
  check_size(written, size, "lz4");
  return out;
}

std::vector<std::uint8_t> bzip2(std::span<const std::uint8_t> in, std::uint64_t size) {
  std::vector<std::uint8_t> out(size);
  // libbz2 counts in unsigned int; a chunk over 4 GiB was refused above.
  auto out_bytes = static_cast<unsigned int>(size);
  // libbz2's API takes non-const pointers but does not write through the source.
  const int status = BZ2_bzBuffToBuffDecompress(
      reinterpret_cast<char*>(out.data()), &out_bytes,
      const_cast<char*>(reinterpret_cast<const char*>(in.data())),
      static_cast<unsigned int>(in.size()), 0, 0);
  if (status != BZ_OK) {
    throw DecompressError("bz2: " + std::string(status == BZ_OUTBUFF_FULL ? "more data than the "
                                                                            "chunk header says"
                                                : status == BZ_UNEXPECTED_EOF ? "stream cut short"
                                                                              : "corrupt stream") +
                          " (libbz2 status " + std::to_string(status) + ")");
  }
  check_size(out_bytes, size, "bz2");
  return out;
}

}  // namespace

std::vector<std::uint8_t> decompress_chunk(std::span<const std::uint8_t> compressed,
                                           ChunkCompression compression,
                                           std::uint64_t uncompressed_size) {
  if (uncompressed_size >= kMaxChunkBytes) {
    throw DecompressError("uncompressed size " + std::to_string(uncompressed_size) +
                          " bytes is implausible");
  }
  switch (compression) {
    case ChunkCompression::None:
      check_size(compressed.size(), uncompressed_size, "uncompressed chunk");
      return {compressed.begin(), compressed.end()};
    case ChunkCompression::Zstd:
      return zstd(compressed, uncompressed_size);
    case ChunkCompression::Lz4Frame:
      return lz4_frame(compressed, uncompressed_size);
    case ChunkCompression::Bzip2:
      return bzip2(compressed, uncompressed_size);
  }
  throw DecompressError("unknown compression");
}

}  // namespace conicloc::io
