#pragma once
// Which topic of a bag holds the Velodyne data: the one named (--topic), or else the only topic of
// type velodyne_msgs/VelodyneScan (packets) or sensor_msgs/PointCloud2 (the driver's clouds).
// Anything else throws TopicError whose message lists every topic with its type, so the user can
// name one.

#include <stdexcept>
#include <string>
#include <vector>

#include "io/bag_reader.hpp"

namespace conicloc::io {

class TopicError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// `requested`: the topic asked for ("" for none).
BagTopic choose_velodyne_topic(const std::vector<BagTopic>& topics, const std::string& requested);

}  // namespace conicloc::io
