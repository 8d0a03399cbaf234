#pragma once
// Writes MCAP files (mcap.dev/spec, version 0) that viewers can seek in: Magic, Header, the data
// section (Schema and Channel records, then Message records in Chunks, each chunk followed by a
// Message Index per channel, then Data End), the summary section (every Schema and Channel again,
// one Statistics record, a Chunk Index per chunk), a Summary Offset per summary group, the Footer
// and the closing Magic. Chunks are zstd-compressed (libzstd) or stored; every CRC32 the format
// has (chunk records, data section, summary) is written.
//
// Message log times are scan times in nanoseconds (the caller's epoch, e.g. UTC); publish time =
// log time. Errors (cannot open, a failed write) throw InputError naming the file.

#include <cstdint>
#include <fstream>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace conicloc::io {

enum class McapChunkCompression { None, Zstd };

struct McapWriterOptions {
  McapChunkCompression compression = McapChunkCompression::Zstd;
  /// A chunk is written once its uncompressed records reach this size (bytes).
  std::size_t chunk_bytes = 1 << 20;
  std::string profile;  ///< the Header's profile ("": none of the well-known profiles)
  std::string library = "conicloc";
};

class McapWriter {
 public:
  /// Creates `path` and writes the magic and the Header; throws InputError if it cannot.
  explicit McapWriter(std::string path, McapWriterOptions options = {});
  /// Closes the file if close() was not called (errors are then lost: call close() to see them).
  ~McapWriter();
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;

  /// A schema (e.g. name "foxglove.PointCloud", encoding "jsonschema", data the schema text);
  /// returns its id (1, 2, ...).
  std::uint16_t add_schema(const std::string& name, const std::string& encoding,
                           std::string_view data);
  /// A channel on `topic` with messages of `schema_id` in `message_encoding` (e.g. "json");
  /// returns its id (0, 1, ...).
  std::uint16_t add_channel(std::uint16_t schema_id, const std::string& topic,
                            const std::string& message_encoding);
  /// One message on `channel_id` (from add_channel) logged at `log_time_ns`.
  void write(std::uint16_t channel_id, std::uint64_t log_time_ns,
             std::span<const std::uint8_t> data);
  void write(std::uint16_t channel_id, std::uint64_t log_time_ns, std::string_view data);

  /// Writes the last chunk, the summary and the footer, and closes the file. Idempotent.
  void close();

  std::uint64_t message_count() const { return message_count_; }

 private:
  void emit(std::span<const std::uint8_t> bytes);
  void emit_record(std::uint8_t opcode, std::span<const std::uint8_t> content);
  void flush_chunk();
  /// Writes the summary section and the Summary Offsets; returns where the offsets start.
  std::uint64_t write_summary();

  std::string path_;
  McapWriterOptions options_;
  std::ofstream file_;
  bool closed_ = false;
  std::uint64_t offset_ = 0;  ///< bytes written so far
  std::uint32_t crc_ = 0;     ///< of the data section, then of the summary section

  std::vector<std::vector<std::uint8_t>> schema_records_;   ///< contents, for the summary
  std::vector<std::vector<std::uint8_t>> channel_records_;  ///< contents, for the summary
  std::vector<std::uint32_t> sequence_;                     ///< next sequence number per channel
  std::vector<std::uint64_t> channel_messages_;             ///< messages per channel

  std::vector<std::uint8_t> chunk_;  ///< the open chunk's uncompressed records
  std::uint64_t chunk_start_ns_ = 0;
  std::uint64_t chunk_end_ns_ = 0;
  /// Per channel in the open chunk: (log time, offset of the message in chunk_).
  std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_index_;
  std::vector<std::vector<std::uint8_t>> chunk_index_records_;  ///< contents, for the summary

  std::uint64_t message_count_ = 0;
  std::uint64_t start_ns_ = 0;
  std::uint64_t end_ns_ = 0;
};

}  // namespace conicloc::io
