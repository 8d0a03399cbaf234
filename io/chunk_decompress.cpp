#include "io/chunk_decompress.hpp"

#include <bzlib.h>
#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
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

// The output grows as data comes out (never beyond the size the header claims), so a corrupt size
// costs nothing until the stream really produces that much.
constexpr std::size_t kGrowthBytes = std::size_t{1} << 20;

std::vector<std::uint8_t> zstd(std::span<const std::uint8_t> in, std::uint64_t size) {
  const std::unique_ptr<ZSTD_DCtx, decltype(&ZSTD_freeDCtx)> context(ZSTD_createDCtx(),
                                                                     ZSTD_freeDCtx);
  if (!context) throw DecompressError("zstd: cannot create a decompression context");
  std::vector<std::uint8_t> out;
  ZSTD_inBuffer input{in.data(), in.size(), 0};
  std::size_t written = 0;
  for (;;) {
    out.resize(static_cast<std::size_t>(std::min<std::uint64_t>(size, written + kGrowthBytes)));
    ZSTD_outBuffer output{out.data(), out.size(), written};
    const std::size_t consumed_before = input.pos;
    const std::size_t status = ZSTD_decompressStream(context.get(), &output, &input);
    if (ZSTD_isError(status)) {
      throw DecompressError(std::string("zstd: ") + ZSTD_getErrorName(status));
    }
    const bool progressed = output.pos > written || input.pos > consumed_before;
    written = output.pos;
    if (status == 0 && input.pos == input.size) break;  // every frame complete
    if (!progressed) {
      throw DecompressError(written == size ? "zstd: more data than the chunk header says"
                                            : "zstd: the frame is cut short");
    }
  }
  out.resize(written);
  check_size(written, size, "zstd");
  return out;
}

std::vector<std::uint8_t> lz4_frame(std::span<const std::uint8_t> in, std::uint64_t size) {
  // An LZ4 sequence expands at most 255-fold: a larger claim is a corrupt header.
  if (size > 255 * static_cast<std::uint64_t>(in.size()) + 1024) {
    throw DecompressError("lz4: " + std::to_string(in.size()) + " bytes cannot hold the " +
                          std::to_string(size) + " the chunk header says");
  }
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
    const std::size_t hint = LZ4F_decompress(context.get(), out.data() + written, &out_bytes,
                                             in.data() + read, &in_bytes, nullptr);
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
  bz_stream stream{};
  if (BZ2_bzDecompressInit(&stream, 0, 0) != BZ_OK) {
    throw DecompressError("bz2: cannot create a decompression stream");
  }
  const std::unique_ptr<bz_stream, decltype(&BZ2_bzDecompressEnd)> guard(&stream,
                                                                         BZ2_bzDecompressEnd);
  // libbz2 takes a non-const pointer to its input but does not write through it; it counts in
  // unsigned int, and chunks over 4 GiB were refused above.
  stream.next_in = const_cast<char*>(reinterpret_cast<const char*>(in.data()));
  stream.avail_in = static_cast<unsigned int>(in.size());
  std::vector<std::uint8_t> out;
  std::size_t written = 0;
  for (;;) {
    out.resize(static_cast<std::size_t>(std::min<std::uint64_t>(size, written + kGrowthBytes)));
    stream.next_out = reinterpret_cast<char*>(out.data() + written);
    stream.avail_out = static_cast<unsigned int>(out.size() - written);
    const unsigned int available_before = stream.avail_in;
    const int status = BZ2_bzDecompress(&stream);
    const std::size_t produced = out.size() - written - stream.avail_out;
    written += produced;
    if (status == BZ_STREAM_END) break;
    if (status != BZ_OK) {
      throw DecompressError("bz2: corrupt stream (libbz2 status " + std::to_string(status) + ")");
    }
    if (produced == 0 && stream.avail_in == available_before) {
      throw DecompressError(written == size ? "bz2: more data than the chunk header says"
                                            : "bz2: stream cut short");
    }
  }
  out.resize(written);
  check_size(written, size, "bz2");
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
