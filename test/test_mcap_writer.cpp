// io/mcap_writer: files read back by conicloc's own MCAP reader (topics from the summary, every
// payload exact, both chunk compressions), and walked record by record through the index: the
// Footer, Summary Offsets, Statistics, Chunk Indexes and Message Indexes point at what they claim,
// and every CRC checks out. Plus io/crc32's check value and an unwritable path.
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "io/byte_cursor.hpp"
#include "io/chunk_decompress.hpp"
#include "io/crc32.hpp"
#include "io/input_error.hpp"
#include "io/mcap_reader.hpp"
#include "io/mcap_writer.hpp"
#include "test/temp_path.hpp"

namespace conicloc::io {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes bytes_of(const std::string& text) {
  return {text.begin(), text.end()};
}

Bytes read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Messages of two topics, the second with an empty payload among them, over `count` log times.
struct Written {
  std::vector<std::string> points;
  std::vector<std::string> notes;
  std::uint64_t first_ns = 1'700'000'000'000'000'000ULL;
  std::uint64_t step_ns = 100'000'000ULL;
};

Written write_file(const std::string& path, McapWriterOptions options, int count) {
  Written written;
  McapWriter writer(path, options);
  const std::uint16_t cloud = writer.add_schema("foxglove.PointCloud", "jsonschema", "{}");
  const std::uint16_t text = writer.add_schema("std_msgs/msg/String", "ros2msg", "string data");
  const std::uint16_t points = writer.add_channel(cloud, "/points", "json");
  const std::uint16_t notes = writer.add_channel(text, "/notes", "cdr");
  for (int i = 0; i < count; ++i) {
    const std::uint64_t t = written.first_ns + static_cast<std::uint64_t>(i) * written.step_ns;
    written.points.push_back("{\"i\":" + std::to_string(i) + ",\"pad\":\"" +
                             std::string(static_cast<std::size_t>(i * 7), 'x') + "\"}");
    writer.write(points, t, written.points.back());
    if (i % 3 == 0) {
      written.notes.push_back(i == 0 ? std::string()
                                     : std::string(static_cast<std::size_t>(i), 'n'));
      writer.write(notes, t, written.notes.back());
    }
  }
  EXPECT_EQ(writer.message_count(), written.points.size() + written.notes.size());
  writer.close();
  return written;
}

std::vector<std::string> read_topic(const std::string& path, const std::string& topic) {
  McapReader reader(path);
  reader.select(topic);
  std::vector<std::string> payloads;
  while (const auto message = reader.next()) {
    payloads.emplace_back(message->data.begin(), message->data.end());
  }
  EXPECT_EQ(reader.counts().bad_messages, 0U);
  EXPECT_EQ(reader.counts().bad_chunks, 0U);
  EXPECT_EQ(reader.counts().truncated_records, 0U);
  return payloads;
}

TEST(Crc32, MatchesTheCheckValueAndContinuesAcrossCalls) {
  const Bytes digits = bytes_of("123456789");
  EXPECT_EQ(crc32(digits), 0xCBF43926U);  // the CRC-32/ISO-HDLC check value
  const std::uint32_t head = crc32(std::span(digits).first(4));
  EXPECT_EQ(crc32(std::span(digits).subspan(4), head), 0xCBF43926U);
  EXPECT_EQ(crc32({}), 0U);
}

class McapWriterRoundTrip : public ::testing::TestWithParam<McapChunkCompression> {};

TEST_P(McapWriterRoundTrip, OurReaderGetsTheTopicsAndEveryPayloadBack) {
  const std::string path = test::unique_temp_path("round_trip.mcap").string();
  // Small chunks: the messages spread over several of them.
  McapWriterOptions options;
  options.compression = GetParam();
  options.chunk_bytes = 300;
  const Written written = write_file(path, options, 40);

  McapReader reader(path);
  const auto topics = reader.topics();
  ASSERT_EQ(topics.size(), 2U);
  EXPECT_EQ(topics[0].name, "/points");
  EXPECT_EQ(topics[0].type, "foxglove.PointCloud");
  EXPECT_EQ(topics[0].encoding_name, "json");
  EXPECT_EQ(topics[1].name, "/notes");
  EXPECT_EQ(topics[1].type, "std_msgs/msg/String");
  EXPECT_EQ(topics[1].encoding, MessageEncoding::Cdr);

  EXPECT_EQ(read_topic(path, "/points"), written.points);
  EXPECT_EQ(read_topic(path, "/notes"), written.notes);
  std::filesystem::remove(path);
}

std::string compression_name(const ::testing::TestParamInfo<McapChunkCompression>& param) {
  return param.param == McapChunkCompression::Zstd ? "zstd" : "stored";
}

INSTANTIATE_TEST_SUITE_P(Compressions, McapWriterRoundTrip,
                         ::testing::Values(McapChunkCompression::None, McapChunkCompression::Zstd),
                         compression_name);

// One record at `offset` of the file: its opcode and content.
struct Record {
  std::uint8_t opcode = 0;
  std::span<const std::uint8_t> content;
  std::uint64_t length = 0;  ///< of the whole record
};

Record record_at(std::span<const std::uint8_t> file, std::uint64_t offset) {
  ByteCursor cursor(file.subspan(offset));
  Record record;
  record.opcode = cursor.u8();
  const std::uint64_t length = cursor.u64();
  record.content = cursor.bytes(length);
  record.length = 9 + length;
  return record;
}

TEST(McapWriter, IndexSummaryAndChecksumsPointAtWhatTheyClaim) {
  const std::string path = test::unique_temp_path("indexed.mcap").string();
  McapWriterOptions options;
  options.chunk_bytes = 500;  // zstd chunks, several of them
  const Written written = write_file(path, options, 30);
  const Bytes file = read_all(path);
  const std::array<std::uint8_t, 8> magic = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
  ASSERT_GT(file.size(), 2 * magic.size() + 29);
  EXPECT_TRUE(std::equal(magic.begin(), magic.end(), file.begin()));
  EXPECT_TRUE(std::equal(magic.begin(), magic.end(), file.end() - 8));
  EXPECT_EQ(record_at(file, 8).opcode, 0x01);  // Header

  // Footer: summary start, summary offset start, CRC of the summary up to the CRC field.
  const std::uint64_t footer_at = file.size() - 8 - 29;
  const Record footer = record_at(file, footer_at);
  ASSERT_EQ(footer.opcode, 0x02);
  ByteCursor footer_fields(footer.content);
  const std::uint64_t summary_start = footer_fields.u64();
  const std::uint64_t summary_offset_start = footer_fields.u64();
  const std::uint32_t summary_crc = footer_fields.u32();
  EXPECT_EQ(summary_crc,
            crc32(std::span(file).subspan(summary_start, footer_at + 25 - summary_start)));

  // Data End, just before the summary: the CRC of everything before it.
  const Record data_end = record_at(file, summary_start - 13);
  ASSERT_EQ(data_end.opcode, 0x0F);
  EXPECT_EQ(ByteCursor(data_end.content).u32(), crc32(std::span(file).first(summary_start - 13)));

  // Summary Offsets: one per group, each group's records all of its opcode, back to back.
  std::map<std::uint8_t, std::pair<std::uint64_t, std::uint64_t>> groups;
  for (std::uint64_t at = summary_offset_start; at < footer_at;) {
    const Record offset = record_at(file, at);
    ASSERT_EQ(offset.opcode, 0x0E);
    ByteCursor fields(offset.content);
    const std::uint8_t opcode = fields.u8();
    const std::uint64_t start = fields.u64();
    groups[opcode] = {start, fields.u64()};
    at += offset.length;
  }
  ASSERT_EQ(groups.size(), 4U);  // Schema, Channel, Statistics, Chunk Index
  std::map<std::uint8_t, std::vector<Record>> summary;
  for (const auto& [opcode, group] : groups) {
    for (std::uint64_t at = group.first; at < group.first + group.second;) {
      summary[opcode].push_back(record_at(file, at));
      EXPECT_EQ(summary[opcode].back().opcode, opcode);
      at += summary[opcode].back().length;
    }
  }
  EXPECT_EQ(summary[0x03].size(), 2U);
  EXPECT_EQ(summary[0x04].size(), 2U);
  ASSERT_EQ(summary[0x0B].size(), 1U);

  ByteCursor statistics(summary[0x0B][0].content);
  const std::uint64_t messages = written.points.size() + written.notes.size();
  EXPECT_EQ(statistics.u64(), messages);
  EXPECT_EQ(statistics.u16(), 2U);  // schemas
  EXPECT_EQ(statistics.u32(), 2U);  // channels
  statistics.skip(8);               // attachments, metadata
  const std::uint32_t chunks = statistics.u32();
  EXPECT_EQ(chunks, summary[0x08].size());
  EXPECT_GT(chunks, 2U);
  EXPECT_EQ(statistics.u64(), written.first_ns);
  EXPECT_EQ(statistics.u64(), written.first_ns + (written.points.size() - 1) * written.step_ns);
  EXPECT_EQ(statistics.u32(), 20U);  // two (channel, count) pairs
  EXPECT_EQ(statistics.u16(), 0U);
  EXPECT_EQ(statistics.u64(), written.points.size());
  EXPECT_EQ(statistics.u16(), 1U);
  EXPECT_EQ(statistics.u64(), written.notes.size());

  // Every Chunk Index: its chunk (CRC of the records), and through its Message Indexes every
  // message, at the log time the index gives.
  std::uint64_t indexed = 0;
  for (const Record& index : summary[0x08]) {
    ByteCursor fields(index.content);
    const std::uint64_t start_ns = fields.u64();
    const std::uint64_t end_ns = fields.u64();
    const std::uint64_t chunk_at = fields.u64();
    const std::uint64_t chunk_length = fields.u64();
    const Record chunk = record_at(file, chunk_at);
    ASSERT_EQ(chunk.opcode, 0x06);
    EXPECT_EQ(chunk.length, chunk_length);
    ByteCursor chunk_fields(chunk.content);
    EXPECT_EQ(chunk_fields.u64(), start_ns);
    EXPECT_EQ(chunk_fields.u64(), end_ns);
    const std::uint64_t uncompressed_size = chunk_fields.u64();
    const std::uint32_t crc = chunk_fields.u32();
    EXPECT_EQ(chunk_fields.prefixed_text(), "zstd");
    const Bytes records = decompress_chunk(chunk_fields.bytes(chunk_fields.u64()),
                                           ChunkCompression::Zstd, uncompressed_size);
    EXPECT_EQ(crc32(records), crc);

    ByteCursor offsets(fields.bytes(fields.u32()));
    std::uint64_t index_bytes = 0;  // the Message Indexes follow the chunk back to back
    while (!offsets.at_end()) {
      const std::uint16_t channel = offsets.u16();
      const std::uint64_t index_at = offsets.u64();
      EXPECT_EQ(index_at, chunk_at + chunk_length + index_bytes);
      const Record message_index = record_at(file, index_at);
      ASSERT_EQ(message_index.opcode, 0x07);
      index_bytes += message_index.length;
      ByteCursor entries(message_index.content);
      EXPECT_EQ(entries.u16(), channel);
      ByteCursor pairs(entries.bytes(entries.u32()));
      while (!pairs.at_end()) {
        const std::uint64_t time_ns = pairs.u64();
        const Record message = record_at(records, pairs.u64());
        ASSERT_EQ(message.opcode, 0x05);
        ByteCursor message_fields(message.content);
        EXPECT_EQ(message_fields.u16(), channel);
        message_fields.skip(4);  // sequence
        EXPECT_EQ(message_fields.u64(), time_ns);
        EXPECT_EQ(message_fields.u64(), time_ns);  // publish time = log time
        EXPECT_GE(time_ns, start_ns);
        EXPECT_LE(time_ns, end_ns);
        ++indexed;
      }
    }
    EXPECT_EQ(fields.u64(), index_bytes);
    EXPECT_EQ(fields.prefixed_text(), "zstd");
    EXPECT_EQ(fields.u64(), chunk_length - 9 - 8 - 8 - 8 - 4 - 8 - 8);  // compressed size
    EXPECT_EQ(fields.u64(), uncompressed_size);
  }
  EXPECT_EQ(indexed, messages);
  std::filesystem::remove(path);
}

TEST(McapWriter, AnUnwritablePathIsAnErrorNamingTheFile) {
  const std::string path = "/nonexistent-conicloc-dir/run.mcap";
  try {
    McapWriter writer(path);
    FAIL() << "no error for " << path;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace conicloc::io
