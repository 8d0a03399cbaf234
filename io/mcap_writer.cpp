#include "io/mcap_writer.hpp"

#include <zstd.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>

#include "io/crc32.hpp"
#include "io/input_error.hpp"

namespace conicloc::io {
namespace {

constexpr std::array<std::uint8_t, 8> kMagic = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};

// Opcodes (spec "Records").
constexpr std::uint8_t kHeader = 0x01;
constexpr std::uint8_t kFooter = 0x02;
constexpr std::uint8_t kSchema = 0x03;
constexpr std::uint8_t kChannel = 0x04;
constexpr std::uint8_t kMessage = 0x05;
constexpr std::uint8_t kChunk = 0x06;
constexpr std::uint8_t kMessageIndex = 0x07;
constexpr std::uint8_t kChunkIndex = 0x08;
constexpr std::uint8_t kStatistics = 0x0B;
constexpr std::uint8_t kSummaryOffset = 0x0E;
constexpr std::uint8_t kDataEnd = 0x0F;

// Little-endian fields appended to a record's content (spec "Serialization").
class Bytes {
 public:
  Bytes() { data.reserve(64); }  // most records are small; also spares GCC 12 a false warning
  Bytes& u8(std::uint8_t v) { return put(v, 1); }
  Bytes& u16(std::uint16_t v) { return put(v, 2); }
  Bytes& u32(std::uint32_t v) { return put(v, 4); }
  Bytes& u64(std::uint64_t v) { return put(v, 8); }
  Bytes& raw(std::span<const std::uint8_t> bytes) { return append(bytes.data(), bytes.size()); }
  Bytes& raw(std::string_view text) { return append(text.data(), text.size()); }
  /// String: uint32 byte length, then the bytes.
  Bytes& text(std::string_view text) {
    return u32(static_cast<std::uint32_t>(text.size())).raw(text);
  }
  /// A whole record: opcode, uint64 content length, content.
  Bytes& record(std::uint8_t opcode, std::span<const std::uint8_t> content) {
    return u8(opcode).u64(content.size()).raw(content);
  }

  std::vector<std::uint8_t> data;

 private:
  Bytes& put(std::uint64_t v, int count) {
    std::array<std::uint8_t, 8> bytes{};
    for (int i = 0; i < count; ++i)
      bytes[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(v >> (8 * i));
    return append(bytes.data(), static_cast<std::size_t>(count));
  }
  Bytes& append(const void* bytes, std::size_t count) {
    const std::size_t at = data.size();
    data.resize(at + count);
    if (count > 0) std::memcpy(data.data() + at, bytes, count);
    return *this;
  }
};

std::vector<std::uint8_t> zstd_compress(std::span<const std::uint8_t> records,
                                        const std::string& path) {
  std::vector<std::uint8_t> out(ZSTD_compressBound(records.size()));
  const std::size_t size =
      ZSTD_compress(out.data(), out.size(), records.data(), records.size(), ZSTD_CLEVEL_DEFAULT);
  if (ZSTD_isError(size) != 0U) {
    throw InputError(path, "chunk",
                     std::string("zstd compression failed: ") + ZSTD_getErrorName(size));
  }
  out.resize(size);
  return out;
}

}  // namespace

McapWriter::McapWriter(std::string path, McapWriterOptions options)
    : path_(std::move(path)), options_(std::move(options)), file_(path_, std::ios::binary) {
  if (!file_) throw InputError(path_, "", "cannot open for writing");
  emit(kMagic);
  Bytes header;
  header.text(options_.profile).text(options_.library);
  emit_record(kHeader, header.data);
}

McapWriter::~McapWriter() {
  try {
    close();
  } catch (const std::exception&) {  // a destructor must not throw; close() reports to callers
  }
}

void McapWriter::emit(std::span<const std::uint8_t> bytes) {
  file_.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
  if (!file_) throw InputError(path_, "byte " + std::to_string(offset_), "write failed");
  crc_ = crc32(bytes, crc_);
  offset_ += bytes.size();
}

void McapWriter::emit_record(std::uint8_t opcode, std::span<const std::uint8_t> content) {
  Bytes prefix;
  prefix.u8(opcode).u64(content.size());
  emit(prefix.data);
  emit(content);
}

std::uint16_t McapWriter::add_schema(const std::string& name, const std::string& encoding,
                                     std::string_view data) {
  const auto id = static_cast<std::uint16_t>(schema_records_.size() + 1);  // 0 means "no schema"
  Bytes schema;
  schema.u16(id).text(name).text(encoding).text(data);  // data: uint32-prefixed bytes
  emit_record(kSchema, schema.data);
  schema_records_.push_back(std::move(schema.data));
  return id;
}

std::uint16_t McapWriter::add_channel(std::uint16_t schema_id, const std::string& topic,
                                      const std::string& message_encoding) {
  const auto id = static_cast<std::uint16_t>(channel_records_.size());
  Bytes channel;
  channel.u16(id).u16(schema_id).text(topic).text(message_encoding).u32(0);  // empty metadata
  emit_record(kChannel, channel.data);
  channel_records_.push_back(std::move(channel.data));
  sequence_.push_back(0);
  channel_messages_.push_back(0);
  return id;
}

void McapWriter::write(std::uint16_t channel_id, std::uint64_t log_time_ns, std::string_view data) {
  write(channel_id, log_time_ns,
        std::span(reinterpret_cast<const std::uint8_t*>(data.data()), data.size()));
}

void McapWriter::write(std::uint16_t channel_id, std::uint64_t log_time_ns,
                       std::span<const std::uint8_t> data) {
  if (channel_id >= channel_records_.size()) {
    throw std::invalid_argument("McapWriter::write: channel " + std::to_string(channel_id) +
                                " was never added");
  }
  if (chunk_.empty()) {
    chunk_start_ns_ = log_time_ns;
    chunk_end_ns_ = log_time_ns;
  }
  chunk_start_ns_ = std::min(chunk_start_ns_, log_time_ns);
  chunk_end_ns_ = std::max(chunk_end_ns_, log_time_ns);
  start_ns_ = message_count_ == 0 ? log_time_ns : std::min(start_ns_, log_time_ns);
  end_ns_ = message_count_ == 0 ? log_time_ns : std::max(end_ns_, log_time_ns);
  chunk_index_[channel_id].emplace_back(log_time_ns, chunk_.size());

  Bytes message;
  message.u16(channel_id).u32(sequence_[channel_id]++).u64(log_time_ns).u64(log_time_ns).raw(data);
  Bytes record;
  record.record(kMessage, message.data);
  chunk_.insert(chunk_.end(), record.data.begin(), record.data.end());
  ++channel_messages_[channel_id];
  ++message_count_;
  if (chunk_.size() >= options_.chunk_bytes) flush_chunk();
}

void McapWriter::flush_chunk() {
  if (chunk_.empty()) return;
  const bool zstd = options_.compression == McapChunkCompression::Zstd;
  const std::vector<std::uint8_t> stored = zstd ? zstd_compress(chunk_, path_) : chunk_;
  const std::string compression = zstd ? "zstd" : "";

  Bytes chunk;
  chunk.u64(chunk_start_ns_).u64(chunk_end_ns_).u64(chunk_.size()).u32(crc32(chunk_));
  chunk.text(compression).u64(stored.size()).raw(stored);
  const std::uint64_t chunk_offset = offset_;
  emit_record(kChunk, chunk.data);
  const std::uint64_t chunk_length = offset_ - chunk_offset;

  // A Message Index per channel right after the chunk: (log time, offset in the records).
  Bytes index_offsets;  // Map<uint16, uint64>: channel -> offset of its Message Index
  const std::uint64_t indexes_offset = offset_;
  for (const auto& [channel, entries] : chunk_index_) {
    index_offsets.u16(channel).u64(offset_);
    Bytes index;
    index.u16(channel).u32(static_cast<std::uint32_t>(entries.size() * 16));
    for (const auto& [time_ns, at] : entries) index.u64(time_ns).u64(at);
    emit_record(kMessageIndex, index.data);
  }

  Bytes chunk_index;
  chunk_index.u64(chunk_start_ns_).u64(chunk_end_ns_).u64(chunk_offset).u64(chunk_length);
  chunk_index.u32(static_cast<std::uint32_t>(index_offsets.data.size())).raw(index_offsets.data);
  chunk_index.u64(offset_ - indexes_offset).text(compression).u64(stored.size()).u64(chunk_.size());
  chunk_index_records_.push_back(std::move(chunk_index.data));

  chunk_.clear();
  chunk_index_.clear();
}

std::uint64_t McapWriter::write_summary() {
  // Summary records grouped by opcode; a Summary Offset per group lets a reader find each.
  struct Group {
    std::uint8_t opcode;
    std::uint64_t start;
    std::uint64_t length;
  };
  std::vector<Group> groups;
  const auto write_group = [&](std::uint8_t opcode,
                               const std::vector<std::vector<std::uint8_t>>& contents) {
    if (contents.empty()) return;
    const std::uint64_t start = offset_;
    for (const auto& content : contents) emit_record(opcode, content);
    groups.push_back({opcode, start, offset_ - start});
  };
  write_group(kSchema, schema_records_);
  write_group(kChannel, channel_records_);  // before Statistics, whose counts refer to them

  Bytes statistics;
  statistics.u64(message_count_)
      .u16(static_cast<std::uint16_t>(schema_records_.size()))
      .u32(static_cast<std::uint32_t>(channel_records_.size()))
      .u32(0)  // attachments
      .u32(0)  // metadata
      .u32(static_cast<std::uint32_t>(chunk_index_records_.size()))
      .u64(start_ns_)
      .u64(end_ns_)
      .u32(static_cast<std::uint32_t>(channel_messages_.size() * 10));
  for (std::size_t channel = 0; channel < channel_messages_.size(); ++channel) {
    statistics.u16(static_cast<std::uint16_t>(channel)).u64(channel_messages_[channel]);
  }
  write_group(kStatistics, {statistics.data});
  write_group(kChunkIndex, chunk_index_records_);

  const std::uint64_t summary_offset_start = offset_;
  for (const Group& group : groups) {
    Bytes summary_offset;
    summary_offset.u8(group.opcode).u64(group.start).u64(group.length);
    emit_record(kSummaryOffset, summary_offset.data);
  }
  return summary_offset_start;
}

void McapWriter::close() {
  if (closed_) return;
  closed_ = true;
  flush_chunk();
  Bytes data_end;
  data_end.u32(crc_);  // of every byte before the Data End record
  emit_record(kDataEnd, data_end.data);

  const std::uint64_t summary_start = offset_;
  crc_ = 0;  // from here: the summary CRC, over the summary, the offsets and the footer's start
  const std::uint64_t summary_offset_start = write_summary();
  Bytes footer_start;  // the Footer up to its CRC field, which the CRC covers
  footer_start.u8(kFooter).u64(8 + 8 + 4).u64(summary_start).u64(summary_offset_start);
  emit(footer_start.data);
  Bytes footer_crc;
  footer_crc.u32(crc_);
  emit(footer_crc.data);
  emit(kMagic);
  file_.close();
  if (!file_) throw InputError(path_, "", "closing failed");
}

}  // namespace conicloc::io
