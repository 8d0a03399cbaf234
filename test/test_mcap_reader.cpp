// MCAP files built record by record: top-level and chunked messages (none, zstd, lz4), a file cut
// inside a record, a chunk that does not decompress, an unknown compression.
#include <gtest/gtest.h>
#include <lz4frame.h>
#include <zstd.h>

#include "io/input_error.hpp"
#include "io/mcap_reader.hpp"
#include "io/open_capture.hpp"
#include "test/bag_bytes.hpp"
#include "test/temp_path.hpp"

namespace conicloc::io {
namespace {

using test::append;
using test::Bytes;

Bytes zstd_compress(const Bytes& in) {
  Bytes out(ZSTD_compressBound(in.size()));
  out.resize(ZSTD_compress(out.data(), out.size(), in.data(), in.size(), 3));
  return out;
}

Bytes lz4_compress(const Bytes& in) {
  Bytes out(LZ4F_compressFrameBound(in.size(), nullptr));
  out.resize(LZ4F_compressFrame(out.data(), out.size(), in.data(), in.size(), nullptr));
  return out;
}

// Magic, schema and channel 1 (/velodyne_packets), channel 2 (/imu), then `body`, then the end.
Bytes mcap_file(const Bytes& body) {
  Bytes file = test::mcap_magic();
  append(file, test::mcap_schema(1, "velodyne_msgs/msg/VelodyneScan"));
  append(file, test::mcap_schema(2, "sensor_msgs/msg/Imu"));
  append(file, test::mcap_channel(1, 1, "/velodyne_packets"));
  append(file, test::mcap_channel(2, 2, "/imu"));
  append(file, body);
  append(file, test::mcap_end());
  return file;
}

std::string write_file(const std::string& name, const Bytes& bytes) {
  const std::string path = test::unique_temp_path(name).string();
  test::write_bytes(path, bytes);
  return path;
}

// Every packet of the capture: its first byte (the packet's index in its message).
std::vector<int> packet_marks(CaptureSource& capture) {
  std::vector<int> marks;
  while (auto datagram = capture.next()) marks.push_back(datagram->payload[0]);
  return marks;
}

TEST(McapReader, ReadsTopLevelAndChunkedMessagesOfTheChosenTopic) {
  Bytes chunk_records = test::mcap_message(1, test::cdr_velodyne_scan(2));
  append(chunk_records, test::mcap_message(2, Bytes{0, 1, 0, 0}));
  Bytes body = test::mcap_message(1, test::cdr_velodyne_scan(3));
  append(body, test::mcap_message(2, Bytes{0, 1, 0, 0}));
  append(body, test::mcap_chunk(chunk_records, "", chunk_records));
  append(body, test::mcap_chunk(chunk_records, "zstd", zstd_compress(chunk_records)));
  append(body, test::mcap_chunk(chunk_records, "lz4", lz4_compress(chunk_records)));
  const std::string path = write_file("good.mcap", mcap_file(body));

  McapReader reader(path);
  const auto topics = reader.topics();
  ASSERT_EQ(topics.size(), 2u);
  EXPECT_EQ(topics[0].name, "/velodyne_packets");
  EXPECT_EQ(topics[0].type, "velodyne_msgs/msg/VelodyneScan");
  EXPECT_EQ(topics[1].type, "sensor_msgs/msg/Imu");

  const auto capture = open_capture(path);
  EXPECT_EQ(capture->format(), "MCAP");
  EXPECT_EQ(packet_marks(*capture), (std::vector<int>{0, 1, 2, 0, 1, 0, 1, 0, 1}));
  EXPECT_EQ(capture->counts().records, 4u);
  EXPECT_EQ(capture->counts().truncated_records, 0u);
  std::filesystem::remove(path);
}

TEST(McapReader, ReadsRos1EncodedMessages) {
  // MCAP written from ROS 1 (e.g. `mcap convert` of a .bag): ros1msg schemas, ros1 messages.
  Bytes file = test::mcap_magic();
  append(file, test::mcap_schema(1, "velodyne_msgs/VelodyneScan"));
  append(file, test::mcap_channel(1, 1, "/velodyne_packets", "ros1"));
  append(file, test::mcap_message(1, test::ros1_velodyne_scan(2)));
  append(file, test::mcap_end());
  const std::string path = write_file("ros1.mcap", file);
  const auto capture = open_capture(path);
  EXPECT_EQ(packet_marks(*capture), (std::vector<int>{0, 1}));
  EXPECT_EQ(capture->counts().bad_messages, 0u);
  std::filesystem::remove(path);
}

TEST(McapReader, ACutFileDeliversEverythingBeforeTheCutAndNamesItsOffset) {
  const Bytes first = test::mcap_message(1, test::cdr_velodyne_scan(1));
  Bytes body = first;
  append(body, test::mcap_message(1, test::cdr_velodyne_scan(2)));
  Bytes file = mcap_file(body);
  const std::size_t second_offset =
      file.size() - test::mcap_end().size() - (body.size() - first.size());
  file.resize(second_offset + 100);  // inside the second message
  const std::string path = write_file("cut.mcap", file);
  const auto capture = open_capture(path);
  EXPECT_EQ(packet_marks(*capture), std::vector<int>{0});
  EXPECT_EQ(capture->counts().truncated_records, 1u);
  ASSERT_TRUE(capture->counts().stop_offset.has_value());
  EXPECT_EQ(*capture->counts().stop_offset, second_offset);
  EXPECT_NE(capture->counts().stop_message.find("runs past the end"), std::string::npos);
  std::filesystem::remove(path);
}

TEST(McapReader, ABrokenChunkOrMessageIsSkippedAndNamed) {
  const Bytes records = test::mcap_message(1, test::cdr_velodyne_scan(2));
  Bytes garbage = zstd_compress(records);
  garbage[garbage.size() / 2] ^= 0xFF;
  garbage.resize(garbage.size() - 4);
  Bytes cut_scan = test::cdr_velodyne_scan(2);
  cut_scan.resize(cut_scan.size() - 10);
  Bytes body = test::mcap_chunk(records, "zstd", garbage);
  append(body, test::mcap_message(1, cut_scan));
  append(body, test::mcap_message(1, test::cdr_velodyne_scan(1)));
  const Bytes file = mcap_file(body);
  const std::size_t chunk_offset = file.size() - test::mcap_end().size() - body.size();
  const std::string path = write_file("broken.mcap", file);
  const auto capture = open_capture(path);
  EXPECT_EQ(packet_marks(*capture), std::vector<int>{0});
  const auto& counts = capture->counts();
  EXPECT_EQ(counts.bad_chunks, 1u);
  EXPECT_EQ(counts.bad_messages, 1u);
  ASSERT_EQ(counts.problems.size(), 2u);
  EXPECT_NE(counts.problems[0].find("chunk at byte " + std::to_string(chunk_offset) + ": zstd"),
            std::string::npos)
      << counts.problems[0];
  EXPECT_NE(counts.problems[1].find("CDR VelodyneScan: packet count 2 at offset 28"),
            std::string::npos)
      << counts.problems[1];
  std::filesystem::remove(path);
}

TEST(McapReader, UnknownCompressionIsAnErrorNamingTheChunk) {
  const Bytes records = test::mcap_message(1, test::cdr_velodyne_scan(1));
  const Bytes file = mcap_file(test::mcap_chunk(records, "brotli", records));
  const std::size_t chunk_offset =
      file.size() - test::mcap_end().size() - test::mcap_chunk(records, "brotli", records).size();
  const std::string path = write_file("brotli.mcap", file);
  try {
    // Without a summary the topics are found by reading the whole file: the error comes at once.
    const auto capture = open_capture(path);
    packet_marks(*capture);
    FAIL() << "a brotli chunk was read";
  } catch (const InputError& e) {
    EXPECT_EQ(e.place(), "chunk at byte " + std::to_string(chunk_offset));
    EXPECT_NE(std::string(e.what()).find("unknown chunk compression 'brotli'"), std::string::npos);
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace conicloc::io
