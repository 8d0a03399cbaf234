#include "io/mcap_reader.hpp"

#include <algorithm>
#include <array>

#include "io/chunk_decompress.hpp"
#include "io/input_error.hpp"

namespace conicloc::io {
namespace {

constexpr std::array<std::uint8_t, 8> kMagic = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
constexpr std::uint64_t kRecordHeaderBytes = 9;  // opcode + uint64 length
constexpr std::uint64_t kFooterRecordBytes = kRecordHeaderBytes + 20;

// Opcodes of the records read here (the others are skipped).
constexpr std::uint8_t kFooter = 0x02;
constexpr std::uint8_t kSchema = 0x03;
constexpr std::uint8_t kChannel = 0x04;
constexpr std::uint8_t kMessage = 0x05;
constexpr std::uint8_t kChunk = 0x06;

std::string at_byte(std::uint64_t offset) {
  return "byte " + std::to_string(offset);
}

}  // namespace

McapReader::McapReader(std::string path) : path_(std::move(path)), file_(path_, std::ios::binary) {
  if (!file_) throw InputError(path_, "", "cannot open");
  file_.seekg(0, std::ios::end);
  file_size_ = static_cast<std::uint64_t>(file_.tellg());
  file_.seekg(0);
  std::array<std::uint8_t, 8> magic{};
  file_.read(reinterpret_cast<char*>(magic.data()), magic.size());
  if (!file_ || magic != kMagic) throw InputError(path_, "file header", "not an MCAP file");
  offset_ = kMagic.size();
}

void McapReader::stop(const std::string& why, std::uint64_t offset) {
  ++counts_.truncated_records;
  counts_.stop_message = why;
  counts_.stop_offset = offset;
  done_ = true;
}

bool McapReader::read_top_level_record() {
  if (done_) return false;
  if (offset_ == file_size_) {  // no footer: a recording cut between records; all of it is read
    done_ = true;
    return false;
  }
  if (file_size_ - offset_ < kRecordHeaderBytes) {
    stop("the file ends inside a record header", offset_);
    return false;
  }
  std::array<std::uint8_t, kRecordHeaderBytes> header{};
  file_.seekg(static_cast<std::streamoff>(offset_));
  file_.read(reinterpret_cast<char*>(header.data()), header.size());
  ByteCursor cursor(header);
  opcode_ = cursor.u8();
  const std::uint64_t length = cursor.u64();
  if (length > file_size_ - offset_ - kRecordHeaderBytes) {
    stop("record of " + std::to_string(length) + " bytes runs past the end of the file", offset_);
    return false;
  }
  record_.resize(static_cast<std::size_t>(length));
  file_.read(reinterpret_cast<char*>(record_.data()), static_cast<std::streamsize>(length));
  if (!file_) {
    stop("read error", offset_);
    return false;
  }
  record_offset_ = offset_;
  offset_ += kRecordHeaderBytes + length;
  return true;
}

std::optional<BagMessage> McapReader::next() {
  for (;;) {
    if (chunk_cursor_ && !chunk_cursor_->at_end()) {
      const std::string place = "chunk at " + at_byte(chunk_offset_) + ", record at " +
                                at_byte(chunk_cursor_->offset()) + " of its records";
      std::uint8_t opcode = 0;
      std::span<const std::uint8_t> content;
      try {
        opcode = chunk_cursor_->u8();
        content = chunk_cursor_->bytes(chunk_cursor_->u64());
      } catch (const TruncatedBytes& e) {
        note_problem(&CaptureCounts::bad_chunks,
                     place + ": " + e.what() + "; rest of chunk skipped");
        chunk_cursor_.reset();
        continue;
      }
      if (auto message = handle(opcode, content, place)) return message;
      continue;
    }
    chunk_cursor_.reset();
    if (!read_top_level_record()) return std::nullopt;
    if (opcode_ == kFooter) {
      done_ = true;
      return std::nullopt;
    }
    if (opcode_ == kChunk) {
      open_chunk(record_);
      continue;
    }
    if (auto message = handle(opcode_, record_, "record at " + at_byte(record_offset_))) {
      return message;
    }
  }
}

std::optional<BagMessage> McapReader::handle(std::uint8_t opcode,
                                             std::span<const std::uint8_t> content,
                                             const std::string& place) {
  ByteCursor cursor(content);
  try {
    if (opcode == kSchema) {
      const std::uint16_t id = cursor.u16();
      Schema schema;
      schema.name = cursor.prefixed_text();
      schema.encoding = cursor.prefixed_text();
      schemas_[id] = schema;
    } else if (opcode == kChannel) {
      const std::uint16_t id = cursor.u16();
      Channel channel;
      channel.schema_id = cursor.u16();
      channel.topic = cursor.prefixed_text();
      channel.message_encoding = cursor.prefixed_text();
      channels_[id] = channel;
    } else if (opcode == kMessage) {
      const std::uint16_t channel_id = cursor.u16();
      cursor.skip(4 + 8 + 8);  // sequence, log time, publish time
      const auto channel = channels_.find(channel_id);
      if (channel == channels_.end()) {
        note_problem(&CaptureCounts::bad_messages, place + ": message on channel " +
                                                       std::to_string(channel_id) +
                                                       " before its Channel record; skipped");
        return std::nullopt;
      }
      if (selected_.empty() || channel->second.topic != selected_) return std::nullopt;
      ++counts_.records;
      return BagMessage{cursor.bytes(cursor.remaining()), place};
    }
  } catch (const TruncatedBytes& e) {
    note_problem(opcode == kMessage ? &CaptureCounts::bad_messages : &CaptureCounts::malformed,
                 place + ": record content cut short (" + e.what() + "); skipped");
  }
  return std::nullopt;
}

void McapReader::open_chunk(std::span<const std::uint8_t> content) {
  const std::string place = "chunk at " + at_byte(record_offset_);
  ByteCursor cursor(content);
  try {
    cursor.skip(8 + 8);  // message start and end time
    const std::uint64_t uncompressed_size = cursor.u64();
    cursor.skip(4);  // CRC of the uncompressed records (0: not computed); not checked
    const std::string compression = cursor.prefixed_text();
    const auto records = cursor.bytes(cursor.u64());
    ChunkCompression codec = ChunkCompression::None;
    if (compression == "zstd") {
      codec = ChunkCompression::Zstd;
    } else if (compression == "lz4") {
      codec = ChunkCompression::Lz4Frame;
    } else if (!compression.empty()) {
      throw InputError(path_, place,
                       "unknown chunk compression '" + compression +
                           "' (conicloc reads uncompressed, zstd and lz4 chunks)");
    }
    chunk_ = decompress_chunk(records, codec, uncompressed_size);
    chunk_offset_ = record_offset_;
    chunk_cursor_.emplace(chunk_);
  } catch (const TruncatedBytes& e) {
    note_problem(&CaptureCounts::bad_chunks,
                 place + ": chunk header cut short (" + e.what() + "); skipped");
  } catch (const DecompressError& e) {
    note_problem(&CaptureCounts::bad_chunks, place + ": " + e.what() + "; skipped");
  }
}

bool McapReader::read_summary() {
  // Footer: opcode, length 20, summary start, summary offset start, summary CRC; then the magic.
  if (file_size_ < 2 * kMagic.size() + kFooterRecordBytes) return false;
  const std::uint64_t footer_offset = file_size_ - kMagic.size() - kFooterRecordBytes;
  std::array<std::uint8_t, kFooterRecordBytes + 8> tail{};
  file_.clear();
  file_.seekg(static_cast<std::streamoff>(footer_offset));
  file_.read(reinterpret_cast<char*>(tail.data()), tail.size());
  if (!file_ || !std::equal(kMagic.begin(), kMagic.end(), tail.begin() + kFooterRecordBytes)) {
    return false;
  }
  ByteCursor footer(tail);
  if (footer.u8() != kFooter || footer.u64() != 20) return false;
  const std::uint64_t summary_start = footer.u64();
  if (summary_start < kMagic.size() || summary_start >= footer_offset) return false;
  // Read the summary section with this reader's own record loop, then rewind to the data.
  const std::uint64_t resume = offset_;
  const bool was_done = done_;
  const std::string selected = selected_;
  const CaptureCounts counts = counts_;  // a broken summary is not a broken data section
  selected_.clear();
  offset_ = summary_start;
  bool complete = false;
  while (read_top_level_record()) {
    if (opcode_ == kFooter) {
      complete = true;
      break;
    }
    if (opcode_ == kSchema || opcode_ == kChannel) handle(opcode_, record_, "summary");
  }
  offset_ = resume;
  done_ = was_done;
  selected_ = selected;
  counts_ = counts;
  file_.clear();
  return complete;
}

std::vector<BagTopic> McapReader::topics() {
  if (read_summary()) return topics_from(channels_, schemas_);
  // No summary: a pass over the whole file collects every channel.
  McapReader pass(path_);
  while (pass.next()) {
  }
  return topics_from(pass.channels_, pass.schemas_);
}

std::vector<BagTopic> McapReader::topics_from(
    const std::map<std::uint16_t, Channel>& channels,
    const std::map<std::uint16_t, Schema>& schemas) const {
  std::vector<BagTopic> topics;
  for (const auto& entry : channels) {
    const Channel& channel = entry.second;  // a lambda may not capture a structured binding (C++17)
    if (std::any_of(topics.begin(), topics.end(),
                    [&](const BagTopic& t) { return t.name == channel.topic; })) {
      continue;
    }
    BagTopic topic;
    topic.name = channel.topic;
    const auto schema = schemas.find(channel.schema_id);
    if (schema != schemas.end()) topic.type = schema->second.name;
    topic.encoding_name = channel.message_encoding;
    if (channel.message_encoding == "cdr") topic.encoding = MessageEncoding::Cdr;
    if (channel.message_encoding == "ros1") topic.encoding = MessageEncoding::Ros1;
    topics.push_back(topic);
  }
  return topics;
}

}  // namespace conicloc::io
