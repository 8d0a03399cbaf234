// ROS 1 bags built record by record: header fields, top-level and chunked messages (none, bz2,
// lz4), a bag cut inside a record, a broken message, an unknown compression.
#include <bzlib.h>
#include <gtest/gtest.h>
#include <lz4frame.h>

#include "io/input_error.hpp"
#include "io/open_capture.hpp"
#include "io/rosbag1_header.hpp"
#include "io/rosbag1_reader.hpp"
#include "test/bag_bytes.hpp"
#include "test/temp_path.hpp"

namespace conicloc::io {
namespace {

using test::append;
using test::Bytes;

Bytes bz2_compress(const Bytes& in) {
  Bytes out(in.size() + in.size() / 100 + 600);
  auto size = static_cast<unsigned int>(out.size());
  BZ2_bzBuffToBuffCompress(reinterpret_cast<char*>(out.data()), &size,
                           const_cast<char*>(reinterpret_cast<const char*>(in.data())),
                           static_cast<unsigned int>(in.size()), 9, 0, 0);
  out.resize(size);
  return out;
}

Bytes lz4_compress(const Bytes& in) {
  Bytes out(LZ4F_compressFrameBound(in.size(), nullptr));
  out.resize(LZ4F_compressFrame(out.data(), out.size(), in.data(), in.size(), nullptr));
  return out;
}

std::string write_file(const std::string& name, const Bytes& bytes) {
  const std::string path = test::unique_temp_path(name).string();
  test::write_bytes(path, bytes);
  return path;
}

std::vector<int> packet_marks(CaptureSource& capture) {
  std::vector<int> marks;
  while (auto datagram = capture.next()) marks.push_back(datagram->payload[0]);
  return marks;
}

TEST(Rosbag1Header, ParsesFieldsAndNamesWhatIsWrong) {
  Bytes bytes = test::ros1_field("op", {0x02});
  append(bytes, test::ros1_field("conn", test::le32_bytes(7)));
  append(bytes, test::ros1_field("topic", test::text_bytes("/a=b")));
  const Rosbag1Header header(bytes);
  EXPECT_EQ(header.op(), 0x02);
  EXPECT_EQ(header.u32("conn"), 7u);
  EXPECT_EQ(header.text("topic"), "/a=b");  // only the first '=' separates
  EXPECT_THROW(header.u64("conn"), HeaderError);
  EXPECT_THROW(header.text("type"), HeaderError);

  Bytes no_equals;
  test::put_le32(no_equals, 3);
  test::put_text(no_equals, "abc");
  EXPECT_THROW(Rosbag1Header{no_equals}, HeaderError);
  Bytes cut = test::ros1_field("topic", test::text_bytes("/velodyne"));
  cut.pop_back();
  try {
    Rosbag1Header{cut};
    FAIL() << "a cut field was read";
  } catch (const HeaderError& e) {
    EXPECT_NE(std::string(e.what()).find("at byte 0"), std::string::npos) << e.what();
  }
}

TEST(Rosbag1Reader, ReadsTopLevelAndChunkedMessagesOfTheChosenTopic) {
  Bytes records = test::ros1_connection(0, "/velodyne_packets", "velodyne_msgs/VelodyneScan");
  append(records, test::ros1_connection(1, "/imu", "sensor_msgs/Imu"));
  append(records, test::ros1_message(0, test::ros1_velodyne_scan(2)));
  append(records, test::ros1_message(1, Bytes(40, 0)));
  Bytes file = test::ros1_start();
  append(file, test::ros1_chunk("none", static_cast<std::uint32_t>(records.size()), records));
  const auto size = static_cast<std::uint32_t>(records.size());
  append(file, test::ros1_chunk("bz2", size, bz2_compress(records)));
  append(file, test::ros1_chunk("lz4", size, lz4_compress(records)));
  append(file, test::ros1_message(0, test::ros1_velodyne_scan(3)));
  const std::string path = write_file("good.bag", file);

  Rosbag1Reader reader(path);
  const auto topics = reader.topics();
  ASSERT_EQ(topics.size(), 2u);
  EXPECT_EQ(topics[0].name, "/velodyne_packets");
  EXPECT_EQ(topics[0].type, "velodyne_msgs/VelodyneScan");
  EXPECT_EQ(topics[1].name, "/imu");

  const auto capture = open_capture(path);
  EXPECT_EQ(capture->format(), "ROS 1 bag");
  EXPECT_EQ(packet_marks(*capture), (std::vector<int>{0, 1, 0, 1, 0, 1, 0, 1, 2}));
  EXPECT_EQ(capture->counts().records, 4u);
  std::filesystem::remove(path);
}

TEST(Rosbag1Reader, ACutBagDeliversEverythingBeforeTheCutAndNamesItsOffset) {
  Bytes file = test::ros1_start();
  append(file, test::ros1_connection(0, "/velodyne_packets", "velodyne_msgs/VelodyneScan"));
  append(file, test::ros1_message(0, test::ros1_velodyne_scan(1)));
  const std::size_t cut_record = file.size();
  append(file, test::ros1_message(0, test::ros1_velodyne_scan(2)));
  file.resize(cut_record + 500);
  const std::string path = write_file("cut.bag", file);
  const auto capture = open_capture(path);
  EXPECT_EQ(packet_marks(*capture), std::vector<int>{0});
  EXPECT_EQ(capture->counts().truncated_records, 1u);
  EXPECT_EQ(capture->counts().stop_offset, std::optional<std::uint64_t>(cut_record));
  std::filesystem::remove(path);
}

TEST(Rosbag1Reader, ABrokenMessageIsSkippedAndNamed) {
  Bytes file = test::ros1_start();
  append(file, test::ros1_connection(0, "/velodyne_packets", "velodyne_msgs/VelodyneScan"));
  const std::size_t bad_record = file.size();
  Bytes bad = test::ros1_velodyne_scan(2);
  bad.resize(bad.size() - 3);
  append(file, test::ros1_message(0, bad));
  append(file, test::ros1_message(0, test::ros1_velodyne_scan(1)));
  const std::string path = write_file("broken.bag", file);
  const auto capture = open_capture(path);
  EXPECT_EQ(packet_marks(*capture), std::vector<int>{0});
  ASSERT_EQ(capture->counts().problems.size(), 1u);
  EXPECT_EQ(capture->counts().bad_messages, 1u);
  EXPECT_EQ(capture->counts().problems[0].rfind("record at byte " + std::to_string(bad_record), 0),
            0u)
      << capture->counts().problems[0];
  std::filesystem::remove(path);
}

TEST(Rosbag1Reader, UnknownCompressionAndNonBagsAreErrors) {
  Bytes file = test::ros1_start();
  const std::size_t chunk_offset = file.size();
  append(file, test::ros1_chunk("gzip", 10, Bytes(10, 0)));
  const std::string path = write_file("gzip.bag", file);
  Rosbag1Reader reader(path);
  reader.select("/velodyne_packets");
  try {
    reader.next();
    FAIL() << "a gzip chunk was read";
  } catch (const InputError& e) {
    EXPECT_EQ(e.place(), "chunk at byte " + std::to_string(chunk_offset));
    EXPECT_NE(std::string(e.what()).find("unknown chunk compression 'gzip'"), std::string::npos);
  }
  Bytes v12 = test::text_bytes("#ROSBAG V1.2\n");
  const std::string old = write_file("old.bag", v12);
  EXPECT_THROW(Rosbag1Reader{old}, InputError);
  std::filesystem::remove(path);
  std::filesystem::remove(old);
}

}  // namespace
}  // namespace conicloc::io
