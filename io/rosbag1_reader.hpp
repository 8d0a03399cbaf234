#pragma once
// Reads ROS 1 bags, format 2.0 (wiki.ros.org/Bags/Format/2.0), front to back: records of a
// header (Rosbag1Header) and data, each with a uint32 length; connection and message-data records
// at top level or inside chunks (compression "none", "bz2" or "lz4", the LZ4 frames of roslz4).
// Index and chunk-info records are skipped, except that topics() reads the connections from the
// index section that the bag header points to (a pass over the file where there is none).
//
// Where the file breaks (a record running past its end) reading stops and every message before is
// delivered; a chunk that does not decompress is counted and skipped; a chunk with an unknown
// compression throws InputError naming its byte offset.

#include <cstdint>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "io/bag_reader.hpp"
#include "io/byte_cursor.hpp"
#include "io/rosbag1_header.hpp"

namespace conicloc::io {

class Rosbag1Reader : public BagReader {
 public:
  /// Opens `path`, checks the version line and reads the bag header record; throws InputError
  /// when it cannot be read or is not a ROS 1 bag of version 2.0.
  explicit Rosbag1Reader(std::string path);

  std::vector<BagTopic> topics() override;
  void select(const std::string& topic) override { selected_ = topic; }
  std::optional<BagMessage> next() override;

 private:
  struct Connection {
    std::string topic;
    std::string type;
  };

  bool read_top_level_record();
  std::optional<BagMessage> handle(std::span<const std::uint8_t> header,
                                   std::span<const std::uint8_t> data, const std::string& place);
  void open_chunk(const Rosbag1Header& header, std::span<const std::uint8_t> data);
  void stop(const std::string& why, std::uint64_t offset);

  std::string path_;
  std::ifstream file_;
  std::uint64_t file_size_ = 0;
  std::uint64_t offset_ = 0;  ///< of the next top-level record
  std::uint64_t index_pos_ = 0;
  bool done_ = false;
  std::uint64_t record_offset_ = 0;
  std::vector<std::uint8_t> header_;
  std::vector<std::uint8_t> data_;
  std::vector<std::uint8_t> chunk_;  ///< decompressed records of the current chunk
  std::optional<ByteCursor> chunk_cursor_;
  std::uint64_t chunk_offset_ = 0;
  std::map<std::uint32_t, Connection> connections_;
  std::string selected_;
};

}  // namespace conicloc::io
