#include "io/open_capture.hpp"

#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "io/bag_capture_source.hpp"
#include "io/bag_topic.hpp"
#include "io/input_error.hpp"
#include "io/mcap_reader.hpp"
#include "io/pcap_reader.hpp"
#include "io/point_cloud2_msg.hpp"
#include "io/ros2_db3_reader.hpp"
#include "io/rosbag1_reader.hpp"

namespace conicloc::io {
namespace {

namespace fs = std::filesystem;

bool starts_with(const std::array<char, 16>& head, std::size_t size, const char* magic,
                 std::size_t magic_size) {
  return size >= magic_size && std::memcmp(head.data(), magic, magic_size) == 0;
}

// A rosbag2 folder: its storage file (one .db3 or .mcap). Split bags are not read yet.
std::string storage_file(const std::string& folder) {
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(folder)) {
    const auto extension = entry.path().extension();
    if (entry.is_regular_file() && (extension == ".db3" || extension == ".mcap")) {
      files.push_back(entry.path().string());
    }
  }
  if (files.size() == 1) return files.front();
  if (files.empty()) {
    throw InputError(folder, "file header",
                     "a directory, and no ROS 2 bag folder (no .db3 or .mcap file in it)");
  }
  throw InputError(folder, "file header",
                   std::to_string(files.size()) +
                       " bag files in the directory (a split bag): name the one to read");
}

}  // namespace

std::string sniff_capture_format(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  std::array<char, 16> head{};
  file.read(head.data(), head.size());
  const auto size = static_cast<std::size_t>(file.gcount());
  if (starts_with(head, size, "\x89MCAP0\r\n", 8)) return "MCAP";
  if (starts_with(head, size, "#ROSBAG V2.0\n", 13)) return "ROS 1 bag";
  if (starts_with(head, size, "SQLite format 3\0", 16)) return "ROS 2 db3";
  if (starts_with(head, size, "\x0A\x0D\x0D\x0A", 4)) return "pcapng";
  static constexpr std::array<const char*, 4> kPcapMagics = {
      "\xA1\xB2\xC3\xD4", "\xD4\xC3\xB2\xA1", "\xA1\xB2\x3C\x4D", "\x4D\x3C\xB2\xA1"};
  for (const char* magic : kPcapMagics) {
    if (starts_with(head, size, magic, 4)) return "pcap";
  }
  return "";
}

std::optional<OpenedBag> open_bag(const std::string& path, const std::string& topic) {
  std::error_code error;
  OpenedBag bag;
  bag.file = fs::is_directory(path, error) ? storage_file(path) : path;
  bag.format = sniff_capture_format(bag.file);
  if (bag.format == "MCAP") {
    bag.reader = std::make_unique<McapReader>(bag.file);
  } else if (bag.format == "ROS 1 bag") {
    bag.reader = std::make_unique<Rosbag1Reader>(bag.file);
  } else if (bag.format == "ROS 2 db3") {
    bag.reader = std::make_unique<Ros2Db3Reader>(bag.file);
  } else {
    return std::nullopt;
  }
  try {
    bag.topic = choose_velodyne_topic(bag.reader->topics(), topic);
  } catch (const TopicError& e) {
    throw InputError(bag.file, "topics", e.what());
  }
  bag.reader->select(bag.topic.name);
  return bag;
}

std::unique_ptr<CaptureSource> open_capture(const std::string& path,
                                            const CaptureOptions& options) {
  auto bag = open_bag(path, options.topic);
  if (!bag) return std::make_unique<PcapReader>(path, options.ports);
  if (is_point_cloud2_type(bag->topic.type)) {
    throw InputError(bag->file, "topics",
                     "topic " + bag->topic.name + " holds point clouds (" + bag->topic.type +
                         "), not Velodyne packets");
  }
  const std::uint16_t data_port =
      options.ports.empty() ? velodyne::kDataPort : options.ports.front();
  return std::make_unique<BagCaptureSource>(bag->file, bag->format, std::move(bag->reader),
                                            bag->topic, data_port);
}

}  // namespace conicloc::io
