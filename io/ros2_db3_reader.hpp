#pragma once
// Reads ROS 2 bags in rosbag2's sqlite3 storage (.db3): the table topics(id, name, type,
// serialization_format, ...) and the table messages(id, topic_id, timestamp, data), data being
// the serialised message (CDR). Messages of the selected topic come in timestamp order. Opened
// read-only; the file is never changed.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/bag_reader.hpp"

struct sqlite3;
struct sqlite3_stmt;

namespace conicloc::io {

class Ros2Db3Reader : public BagReader {
 public:
  /// Opens `path`; throws InputError when it is not an SQLite database with rosbag2's tables.
  explicit Ros2Db3Reader(std::string path);
  ~Ros2Db3Reader() override;
  Ros2Db3Reader(const Ros2Db3Reader&) = delete;
  Ros2Db3Reader& operator=(const Ros2Db3Reader&) = delete;

  std::vector<BagTopic> topics() override { return topics_; }
  void select(const std::string& topic) override;
  std::optional<BagMessage> next() override;

 private:
  std::string path_;
  sqlite3* db_ = nullptr;
  sqlite3_stmt* messages_ = nullptr;
  std::vector<BagTopic> topics_;
};

}  // namespace conicloc::io
