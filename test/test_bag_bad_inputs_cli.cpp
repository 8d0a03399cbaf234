// Bad bags through the real `conicloc` program: a topic whose type is not VelodyneScan given with
// --topic (decode and localize name the topic and its type and list the bag's topics), and a chunk
// of an unknown compression (named with its file and byte offset). Bags built record by record.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "test/bag_bytes.hpp"
#include "test/cli_run.hpp"
#include "test/temp_path.hpp"

namespace {

namespace fs = std::filesystem;
using conicloc::test::append;
using conicloc::test::Bytes;
using conicloc::test::slurp;

Bytes cdr_string(const std::string& text) {
  Bytes out = {0x00, 0x01, 0x00, 0x00};
  conicloc::test::put_le32(out, static_cast<std::uint32_t>(text.size() + 1));
  conicloc::test::put_text(out, text);
  out.push_back(0);
  return out;
}

// /velodyne_packets (VelodyneScan) and /notes (std_msgs/msg/String), one message each, the
// messages in a chunk of `compression` (stored uncompressed whatever it says).
Bytes mcap_bag(const std::string& compression) {
  Bytes records = conicloc::test::mcap_message(1, conicloc::test::cdr_velodyne_scan(2));
  append(records, conicloc::test::mcap_message(2, cdr_string("hello")));
  Bytes file = conicloc::test::mcap_magic();
  append(file, conicloc::test::mcap_schema(1, "velodyne_msgs/msg/VelodyneScan"));
  append(file, conicloc::test::mcap_schema(2, "std_msgs/msg/String"));
  append(file, conicloc::test::mcap_channel(1, 1, "/velodyne_packets"));
  append(file, conicloc::test::mcap_channel(2, 2, "/notes"));
  append(file, conicloc::test::mcap_chunk(records, compression, records));
  append(file, conicloc::test::mcap_end());
  return file;
}

Bytes ros1_bag() {
  Bytes file = conicloc::test::ros1_start();
  append(file,
         conicloc::test::ros1_connection(0, "/velodyne_packets", "velodyne_msgs/VelodyneScan"));
  append(file, conicloc::test::ros1_connection(1, "/notes", "std_msgs/String"));
  append(file, conicloc::test::ros1_message(0, conicloc::test::ros1_velodyne_scan(2)));
  Bytes note;
  conicloc::test::put_le32(note, 5);
  conicloc::test::put_text(note, "hello");
  append(file, conicloc::test::ros1_message(1, note));
  return file;
}

class BagBadInputCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = conicloc::test::unique_temp_path("bag_bad_inputs_cli");
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const Bytes& bytes) {
    const fs::path path = dir_ / name;
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()),
               static_cast<std::streamsize>(bytes.size()));
    return path;
  }
  // Runs `arguments`; expects a failure whose log holds every one of `expected`.
  void expect_refused(const std::string& arguments, const std::vector<std::string>& expected) {
    const fs::path log = dir_ / "run.log";
    const int code = conicloc::test::run_conicloc(arguments, log);
    const std::string text = slurp(log);
    EXPECT_GT(code, 0) << arguments << "\n" << text;
    for (const auto& part : expected)
      EXPECT_NE(text.find(part), std::string::npos) << part << "\n" << text;
  }
  fs::path dir_;
};

TEST_F(BagBadInputCli, ATopicOfAnotherTypeIsRefusedNamingTopicTypeAndFile) {
  const fs::path mcap = write("two_topics.mcap", mcap_bag(""));
  const fs::path bag = write("two_topics.bag", ros1_bag());
  const std::vector<std::string> mcap_expected = {
      mcap.string(), "topic /notes holds std_msgs/msg/String, not velodyne_msgs/VelodyneScan",
      "/velodyne_packets  (velodyne_msgs/msg/VelodyneScan, cdr)"};
  const std::vector<std::string> bag_expected = {
      bag.string(), "topic /notes holds std_msgs/String, not velodyne_msgs/VelodyneScan",
      "/velodyne_packets  (velodyne_msgs/VelodyneScan, ros1)"};
  expect_refused("decode " + mcap.string() + " --topic /notes", mcap_expected);
  expect_refused("decode " + bag.string() + " --topic /notes", bag_expected);
  const std::string out = " --out " + (dir_ / "poses.tum").string();
  expect_refused("localize --pcap " + mcap.string() + " --topic /notes" + out, mcap_expected);
  expect_refused("localize --pcap " + bag.string() + " --topic /notes" + out, bag_expected);

  // The right topic of the same bags is read: both packets of the message reach the decoder
  // (which rejects their filler bytes: no Velodyne data, exit 2, but no topic error).
  for (const fs::path& path : {mcap, bag}) {
    const fs::path log = dir_ / "good.log";
    (void)conicloc::test::run_conicloc(
        "decode " + path.string() + " --topic /velodyne_packets --stats", log);
    EXPECT_NE(slurp(log).find("packets_read: 2"), std::string::npos) << slurp(log);
    EXPECT_EQ(slurp(log).find("holds"), std::string::npos) << slurp(log);
  }
}

TEST_F(BagBadInputCli, AChunkOfUnknownCompressionIsAnErrorNamingFileAndOffset) {
  const fs::path mcap = write("brotli.mcap", mcap_bag("brotli"));
  expect_refused("decode " + mcap.string(),
                 {mcap.string(), "unknown chunk compression 'brotli'", "byte "});
}

}  // namespace
