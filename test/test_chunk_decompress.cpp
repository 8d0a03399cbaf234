// Chunk decompression: each codec round-trips a chunk larger than the output's growth step, and a
// stream that is cut, corrupt, or longer or shorter than its header says is a DecompressError.
#include <bzlib.h>
#include <gtest/gtest.h>
#include <lz4frame.h>
#include <zstd.h>

#include "io/chunk_decompress.hpp"

namespace conicloc::io {
namespace {

using Bytes = std::vector<std::uint8_t>;

// 3 MiB of bytes that compress, but not to nothing.
Bytes chunk() {
  Bytes bytes(3u << 20);
  std::uint32_t state = 12345;
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    state = state * 1664525u + 1013904223u;
    bytes[i] = static_cast<std::uint8_t>((state >> 28) + (i / 4096 % 7));
  }
  return bytes;
}

Bytes compress(const Bytes& in, ChunkCompression codec) {
  Bytes out;
  if (codec == ChunkCompression::Zstd) {
    out.resize(ZSTD_compressBound(in.size()));
    out.resize(ZSTD_compress(out.data(), out.size(), in.data(), in.size(), 1));
  } else if (codec == ChunkCompression::Lz4Frame) {
    out.resize(LZ4F_compressFrameBound(in.size(), nullptr));
    out.resize(LZ4F_compressFrame(out.data(), out.size(), in.data(), in.size(), nullptr));
  } else if (codec == ChunkCompression::Bzip2) {
    out.resize(in.size() + in.size() / 100 + 600);
    auto size = static_cast<unsigned int>(out.size());
    BZ2_bzBuffToBuffCompress(reinterpret_cast<char*>(out.data()), &size,
                             const_cast<char*>(reinterpret_cast<const char*>(in.data())),
                             static_cast<unsigned int>(in.size()), 1, 0, 0);
    out.resize(size);
  } else {
    out = in;
  }
  return out;
}

class ChunkDecompress : public ::testing::TestWithParam<ChunkCompression> {};

TEST_P(ChunkDecompress, RoundTripsAndRefusesWrongSizesAndCutStreams) {
  const Bytes original = chunk();
  const Bytes packed = compress(original, GetParam());
  EXPECT_EQ(decompress_chunk(packed, GetParam(), original.size()), original);
  EXPECT_THROW(decompress_chunk(packed, GetParam(), original.size() - 1), DecompressError);
  EXPECT_THROW(decompress_chunk(packed, GetParam(), original.size() + 1), DecompressError);
  const Bytes cut(packed.begin(), packed.begin() + static_cast<std::ptrdiff_t>(packed.size() / 2));
  EXPECT_THROW(decompress_chunk(cut, GetParam(), original.size()), DecompressError);
}

INSTANTIATE_TEST_SUITE_P(Codecs, ChunkDecompress,
                         ::testing::Values(ChunkCompression::None, ChunkCompression::Zstd,
                                           ChunkCompression::Lz4Frame, ChunkCompression::Bzip2));

TEST(ChunkDecompressErrors, CorruptStreamsAndImplausibleSizes) {
  const Bytes original = chunk();
  for (const auto codec :
       {ChunkCompression::Zstd, ChunkCompression::Lz4Frame, ChunkCompression::Bzip2}) {
    Bytes packed = compress(original, codec);
    for (std::size_t i = 16; i < packed.size(); i += 97) packed[i] ^= 0x5A;
    EXPECT_THROW(decompress_chunk(packed, codec, original.size()), DecompressError);
  }
  // 100 bytes of LZ4 cannot hold a gigabyte; nor is any chunk 5 GiB.
  EXPECT_THROW(decompress_chunk(Bytes(100, 0), ChunkCompression::Lz4Frame, 1u << 30),
               DecompressError);
  EXPECT_THROW(decompress_chunk(Bytes(100, 0), ChunkCompression::Zstd, 5ull << 30),
               DecompressError);
}

}  // namespace
}  // namespace conicloc::io
