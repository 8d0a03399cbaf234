#pragma once
// Reads MCAP files (mcap.dev/spec, version 0) front to back: records of an opcode byte, a uint64
// length and the content; Schema, Channel and Message records at top level or inside Chunks
// (compression "", "zstd" or "lz4" frames). Index and summary records are skipped, except that
// topics() reads the channels from the summary section when the footer points to one. Messages
// are delivered as they appear in the file (MCAP writers append in log-time order per channel).
//
// Where the file breaks (a record running past its end), reading stops and every message before
// is delivered; a chunk that does not decompress is counted and skipped; a chunk with an unknown
// compression throws InputError naming its byte offset.

#include <cstdint>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "io/bag_reader.hpp"
#include "io/byte_cursor.hpp"

namespace conicloc::io {

class McapReader : public BagReader {
 public:
  /// Opens `path` and checks the magic; throws InputError when it cannot be read or is not MCAP.
  explicit McapReader(std::string path);

  std::vector<BagTopic> topics() override;
  void select(const std::string& topic) override { selected_ = topic; }
  std::optional<BagMessage> next() override;

 private:
  struct Schema {
    std::string name;
    std::string encoding;
  };
  struct Channel {
    std::string topic;
    std::uint16_t schema_id = 0;
    std::string message_encoding;
  };

  bool read_top_level_record();
  std::optional<BagMessage> handle(std::uint8_t opcode, std::span<const std::uint8_t> content,
                                   const std::string& place);
  void open_chunk(std::span<const std::uint8_t> content);
  void stop(const std::string& why, std::uint64_t offset);
  std::vector<BagTopic> topics_from(const std::map<std::uint16_t, Channel>& channels,
                                    const std::map<std::uint16_t, Schema>& schemas) const;
  bool read_summary();

  std::string path_;
  std::ifstream file_;
  std::uint64_t file_size_ = 0;
  std::uint64_t offset_ = 0;  ///< of the next top-level record
  bool done_ = false;
  std::uint8_t opcode_ = 0;
  std::uint64_t record_offset_ = 0;
  std::vector<std::uint8_t> record_;
  std::vector<std::uint8_t> chunk_;  ///< decompressed records of the current chunk
  std::optional<ByteCursor> chunk_cursor_;
  std::uint64_t chunk_offset_ = 0;
  std::map<std::uint16_t, Schema> schemas_;
  std::map<std::uint16_t, Channel> channels_;
  std::string selected_;
};

}  // namespace conicloc::io
