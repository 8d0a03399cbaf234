#include "io/open_capture.hpp"

#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "io/bag_capture_source.hpp"
#include "io/input_error.hpp"
#include "io/mcap_reader.hpp"
#include "io/pcap_reader.hpp"
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

std::unique_ptr<CaptureSource> open_capture(const std::string& path,
                                            const CaptureOptions& options) {
  std::error_code error;
  const std::string file = fs::is_directory(path, error) ? storage_file(path) : path;
  const std::string format = sniff_capture_format(file);
  const std::uint16_t data_port =
      options.ports.empty() ? velodyne::kDataPort : options.ports.front();
  std::unique_ptr<BagReader> reader;
  if (format == "MCAP") {
    reader = std::make_unique<McapReader>(file);
  } else if (format == "ROS 1 bag") {
    reader = std::make_unique<Rosbag1Reader>(file);
  } else if (format == "ROS 2 db3") {
    reader = std::make_unique<Ros2Db3Reader>(file);
  } else {
    return std::make_unique<PcapReader>(file, options.ports);
  }
  return std::make_unique<BagCaptureSource>(file, format, std::move(reader), options.topic,
                                            data_port);
}

}  // namespace conicloc::io
