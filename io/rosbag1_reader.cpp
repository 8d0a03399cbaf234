#include "io/rosbag1_reader.hpp"

#include <algorithm>
#include <array>
#include <cstring>

#include "io/chunk_decompress.hpp"
#include "io/input_error.hpp"

namespace conicloc::io {
namespace {

constexpr char kVersionLine[] = "#ROSBAG V2.0\n";
constexpr std::size_t kVersionBytes = sizeof kVersionLine - 1;

// Record op codes.
constexpr std::uint8_t kMessageData = 0x02;
constexpr std::uint8_t kBagHeader = 0x03;
constexpr std::uint8_t kChunk = 0x05;
constexpr std::uint8_t kConnection = 0x07;

std::string at_byte(std::uint64_t offset) {
  return "byte " + std::to_string(offset);
}

}  // namespace

Rosbag1Reader::Rosbag1Reader(std::string path)
    : path_(std::move(path)), file_(path_, std::ios::binary) {
  if (!file_) throw InputError(path_, "", "cannot open");
  file_.seekg(0, std::ios::end);
  file_size_ = static_cast<std::uint64_t>(file_.tellg());
  file_.seekg(0);
  std::array<char, kVersionBytes> version{};
  file_.read(version.data(), version.size());
  if (!file_ || std::memcmp(version.data(), kVersionLine, kVersionBytes) != 0) {
    throw InputError(path_, "file header", "not a ROS 1 bag of version 2.0");
  }
  offset_ = kVersionBytes;
  if (!read_top_level_record()) {
    throw InputError(path_, "bag header record at " + at_byte(kVersionBytes),
                     counts_.stop_message.empty() ? "missing" : counts_.stop_message);
  }
  try {
    const Rosbag1Header header(header_);
    if (header.op() != kBagHeader) throw HeaderError("the first record is not the bag header");
    index_pos_ = header.u64("index_pos");
  } catch (const HeaderError& e) {
    throw InputError(path_, "bag header record at " + at_byte(kVersionBytes), e.what());
  }
}

void Rosbag1Reader::stop(const std::string& why, std::uint64_t offset) {
  ++counts_.truncated_records;
  counts_.stop_message = why;
  counts_.stop_offset = offset;
  done_ = true;
}

bool Rosbag1Reader::read_top_level_record() {
  if (done_) return false;
  if (offset_ == file_size_) {
    done_ = true;
    return false;
  }
  // header length, header, data length, data
  const auto read_block = [&](std::vector<std::uint8_t>& block, const char* what) {
    std::array<std::uint8_t, 4> length_bytes{};
    const std::uint64_t at = static_cast<std::uint64_t>(file_.tellg());
    if (file_size_ - at < 4) {
      stop(std::string("the file ends inside the record's ") + what + " length", offset_);
      return false;
    }
    file_.read(reinterpret_cast<char*>(length_bytes.data()), 4);
    const std::uint32_t length = ByteCursor(length_bytes).u32();
    if (length > file_size_ - at - 4) {
      stop(std::string("record ") + what + " of " + std::to_string(length) +
               " bytes runs past the end of the file",
           offset_);
      return false;
    }
    block.resize(length);
    file_.read(reinterpret_cast<char*>(block.data()), length);
    if (!file_) {
      stop("read error", offset_);
      return false;
    }
    return true;
  };
  file_.clear();
  file_.seekg(static_cast<std::streamoff>(offset_));
  if (!read_block(header_, "header") || !read_block(data_, "data")) return false;
  record_offset_ = offset_;
  offset_ += 8 + header_.size() + data_.size();
  return true;
}

std::optional<BagMessage> Rosbag1Reader::next() {
  for (;;) {
    if (chunk_cursor_ && !chunk_cursor_->at_end()) {
      const std::string place = "chunk at " + at_byte(chunk_offset_) + ", record at " +
                                at_byte(chunk_cursor_->offset()) + " of its records";
      std::span<const std::uint8_t> header;
      std::span<const std::uint8_t> data;
      try {
        header = chunk_cursor_->bytes(chunk_cursor_->u32());
        data = chunk_cursor_->bytes(chunk_cursor_->u32());
      } catch (const TruncatedBytes& e) {
        note_problem(&CaptureCounts::bad_chunks,
                     place + ": " + e.what() + "; rest of chunk skipped");
        chunk_cursor_.reset();
        continue;
      }
      if (auto message = handle(header, data, place)) return message;
      continue;
    }
    chunk_cursor_.reset();
    if (!read_top_level_record()) return std::nullopt;
    if (auto message = handle(header_, data_, "record at " + at_byte(record_offset_))) {
      return message;
    }
  }
}

std::optional<BagMessage> Rosbag1Reader::handle(std::span<const std::uint8_t> header_bytes,
                                                std::span<const std::uint8_t> data,
                                                const std::string& place) {
  std::optional<std::uint8_t> op;
  try {
    const Rosbag1Header header(header_bytes);
    op = header.op();
    if (op == kChunk) {
      open_chunk(header, data);
    } else if (op == kConnection) {
      Connection connection;
      connection.topic = header.text("topic");
      connection.type = Rosbag1Header(data).text("type");
      connections_[header.u32("conn")] = connection;
    } else if (op == kMessageData) {
      const auto connection = connections_.find(header.u32("conn"));
      if (connection == connections_.end()) {
        note_problem(&CaptureCounts::bad_messages, place + ": message on connection " +
                                                       std::to_string(header.u32("conn")) +
                                                       " before its connection record; skipped");
        return std::nullopt;
      }
      if (selected_.empty() || connection->second.topic != selected_) return std::nullopt;
      ++counts_.records;
      return BagMessage{data, place};
    }
  } catch (const HeaderError& e) {
    note_problem(op == kMessageData ? &CaptureCounts::bad_messages : &CaptureCounts::malformed,
                 place + ": " + e.what() + "; skipped");
  }
  return std::nullopt;
}

void Rosbag1Reader::open_chunk(const Rosbag1Header& header, std::span<const std::uint8_t> data) {
  const std::string place = "chunk at " + at_byte(record_offset_);
  const std::string compression = header.text("compression");
  ChunkCompression codec = ChunkCompression::None;
  if (compression == "bz2") {
    codec = ChunkCompression::Bzip2;
  } else if (compression == "lz4") {
    codec = ChunkCompression::Lz4Frame;
  } else if (compression != "none") {
    throw InputError(path_, place,
                     "unknown chunk compression '" + compression +
                         "' (conicloc reads none, bz2 and lz4 chunks)");
  }
  try {
    chunk_ = decompress_chunk(data, codec, header.u32("size"));
    chunk_offset_ = record_offset_;
    chunk_cursor_.emplace(chunk_);
  } catch (const DecompressError& e) {
    note_problem(&CaptureCounts::bad_chunks, place + ": " + e.what() + "; skipped");
  }
}

std::vector<BagTopic> Rosbag1Reader::topics() {
  Rosbag1Reader pass(path_);
  if (index_pos_ > kVersionBytes && index_pos_ < file_size_) {
    // The index section: the connection records, then one chunk-info record per chunk.
    pass.offset_ = index_pos_;
    while (pass.next()) {
    }
  }
  if (pass.connections_.empty()) {  // no index (a bag not closed), or a broken one
    Rosbag1Reader whole(path_);
    while (whole.next()) {
    }
    pass.connections_ = whole.connections_;
  }
  std::vector<BagTopic> topics;
  for (const auto& entry : pass.connections_) {
    const Connection& connection = entry.second;  // a lambda may not capture a structured binding
    if (std::any_of(topics.begin(), topics.end(),
                    [&](const BagTopic& t) { return t.name == connection.topic; })) {
      continue;
    }
    topics.push_back({connection.topic, connection.type, "ros1", MessageEncoding::Ros1});
  }
  return topics;
}

}  // namespace conicloc::io
