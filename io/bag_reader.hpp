#pragma once
// What the three bag formats have in common, as the capture source sees them: a list of topics
// with their types, and the messages of one chosen topic in file order, each with its place in the
// file for messages. Implemented by McapReader, Rosbag1Reader and Ros2Db3Reader.

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "io/capture_source.hpp"
#include "io/velodyne_scan_msg.hpp"

namespace conicloc::io {

struct BagTopic {
  std::string name;
  std::string type;  ///< "velodyne_msgs/VelodyneScan", "sensor_msgs/msg/PointCloud2", ...
  std::string encoding_name;                ///< as the bag says: "ros1", "cdr", ...
  std::optional<MessageEncoding> encoding;  ///< nullopt when conicloc cannot read it
};

struct BagMessage {
  std::span<const std::uint8_t> data;  ///< valid until the next call to next()
  std::string place;                   ///< "chunk at byte 4711, message 3", "messages row 17"
};

class BagReader {
 public:
  BagReader() { counts_.bag = true; }
  virtual ~BagReader() = default;
  /// Every topic of the bag (read from its index where it has one, else from a pass over it).
  virtual std::vector<BagTopic> topics() = 0;
  /// Restricts next() to the messages of `topic`; call before the first next().
  virtual void select(const std::string& topic) = 0;
  /// The next message of the selected topic, or nullopt at the end (or where the file broke:
  /// then counts().truncated_records is 1 and stop_message says why). Throws InputError where a
  /// message cannot be reached at all (an unknown chunk compression).
  virtual std::optional<BagMessage> next() = 0;
  /// Messages delivered, chunks skipped, where reading stopped.
  CaptureCounts& counts() { return counts_; }

 protected:
  /// Counts a skipped chunk or message and names the first few.
  void note_problem(std::size_t CaptureCounts::*counter, const std::string& text) {
    ++(counts_.*counter);
    if (counts_.problems.size() < CaptureCounts::kNamedProblems) counts_.problems.push_back(text);
  }
  CaptureCounts counts_;
};

}  // namespace conicloc::io
