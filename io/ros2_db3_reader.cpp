#include "io/ros2_db3_reader.hpp"

#include <sqlite3.h>

#include "io/input_error.hpp"

namespace conicloc::io {
namespace {

std::string column_text(sqlite3_stmt* statement, int column) {
  const unsigned char* text = sqlite3_column_text(statement, column);
  return text ? reinterpret_cast<const char*>(text) : "";
}

}  // namespace

Ros2Db3Reader::Ros2Db3Reader(std::string path) : path_(std::move(path)) {
  if (sqlite3_open_v2(path_.c_str(), &db_, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    const std::string why = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    db_ = nullptr;
    throw InputError(path_, "", "cannot open as SQLite database (" + why + ")");
  }
  sqlite3_stmt* statement = nullptr;
  if (sqlite3_prepare_v2(db_, "SELECT name, type, serialization_format FROM topics ORDER BY id", -1,
                         &statement, nullptr) != SQLITE_OK) {
    const std::string why = sqlite3_errmsg(db_);
    sqlite3_close(db_);
    db_ = nullptr;
    throw InputError(path_, "table topics", "not a ROS 2 bag (" + why + ")");
  }
  int status = SQLITE_ROW;
  while ((status = sqlite3_step(statement)) == SQLITE_ROW) {
    BagTopic topic;
    topic.name = column_text(statement, 0);
    topic.type = column_text(statement, 1);
    topic.encoding_name = column_text(statement, 2);
    if (topic.encoding_name == "cdr") topic.encoding = MessageEncoding::Cdr;
    topics_.push_back(topic);
  }
  sqlite3_finalize(statement);
  if (status != SQLITE_DONE) {
    const std::string why = sqlite3_errmsg(db_);
    sqlite3_close(db_);
    db_ = nullptr;
    throw InputError(path_, "table topics", why);
  }
}

Ros2Db3Reader::~Ros2Db3Reader() {
  sqlite3_finalize(messages_);
  sqlite3_close(db_);
}

void Ros2Db3Reader::select(const std::string& topic) {
  sqlite3_finalize(messages_);
  messages_ = nullptr;
  const char* query =
      "SELECT messages.id, messages.data FROM messages JOIN topics ON messages.topic_id = "
      "topics.id WHERE topics.name = ?1 ORDER BY messages.timestamp, messages.id";
  if (sqlite3_prepare_v2(db_, query, -1, &messages_, nullptr) != SQLITE_OK) {
    throw InputError(path_, "table messages", sqlite3_errmsg(db_));
  }
  sqlite3_bind_text(messages_, 1, topic.c_str(), -1, SQLITE_TRANSIENT);
}

std::optional<BagMessage> Ros2Db3Reader::next() {
  if (!messages_) return std::nullopt;
  const int status = sqlite3_step(messages_);
  if (status == SQLITE_ROW) {
    ++counts_.records;
    const auto* data = static_cast<const std::uint8_t*>(sqlite3_column_blob(messages_, 1));
    const auto size = static_cast<std::size_t>(sqlite3_column_bytes(messages_, 1));
    // The blob stays valid until the next step, i.e. the next call.
    return BagMessage{std::span<const std::uint8_t>(data, data ? size : 0),
                      "messages row id " + std::to_string(sqlite3_column_int64(messages_, 0))};
  }
  if (status != SQLITE_DONE) {
    ++counts_.truncated_records;
    counts_.stop_message = std::string("SQLite: ") + sqlite3_errmsg(db_);
  }
  sqlite3_finalize(messages_);
  messages_ = nullptr;
  return std::nullopt;
}

}  // namespace conicloc::io
