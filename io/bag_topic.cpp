#include "io/bag_topic.hpp"

#include <algorithm>

#include "io/point_cloud2_msg.hpp"

namespace conicloc::io {
namespace {

std::string topic_list(const std::vector<BagTopic>& topics) {
  if (topics.empty()) return "the bag has no topics";
  std::string text = "topics in the bag:";
  for (const auto& topic : topics) {
    text += "\n  " + topic.name + "  (" + (topic.type.empty() ? "no type" : topic.type) + ", " +
            (topic.encoding_name.empty() ? "no encoding" : topic.encoding_name) + ")";
  }
  return text;
}

// velodyne_msgs/VelodyneScan (packets) or sensor_msgs/PointCloud2 (the driver's clouds).
bool is_velodyne_type(const std::string& type) {
  return is_velodyne_scan_type(type) || is_point_cloud2_type(type);
}

void check_readable(const BagTopic& topic, const std::vector<BagTopic>& topics) {
  if (!is_velodyne_type(topic.type)) {
    throw TopicError("topic " + topic.name + " holds " + topic.type + ", not " +
                     std::string(kVelodyneScanRos1Type) + " or " +
                     std::string(kPointCloud2Ros1Type) + " (or their ROS 2 names); " +
                     topic_list(topics));
  }
  if (!topic.encoding) {
    throw TopicError("topic " + topic.name + " is encoded as '" + topic.encoding_name +
                     "'; conicloc reads ros1 and cdr messages");
  }
}

}  // namespace

BagTopic choose_velodyne_topic(const std::vector<BagTopic>& topics, const std::string& requested) {
  if (!requested.empty()) {
    const auto found = std::find_if(topics.begin(), topics.end(),
                                    [&](const BagTopic& t) { return t.name == requested; });
    if (found == topics.end())
      throw TopicError("no topic " + requested + "; " + topic_list(topics));
    check_readable(*found, topics);
    return *found;
  }
  std::vector<BagTopic> scans;
  std::copy_if(topics.begin(), topics.end(), std::back_inserter(scans),
               [](const BagTopic& t) { return is_velodyne_type(t.type); });
  if (scans.size() == 1) {
    check_readable(scans.front(), topics);
    return scans.front();
  }
  throw TopicError((scans.empty() ? std::string("no topic of type velodyne_msgs/VelodyneScan or "
                                                "sensor_msgs/PointCloud2")
                                  : std::to_string(scans.size()) +
                                        " topics of type velodyne_msgs/VelodyneScan or "
                                        "sensor_msgs/PointCloud2: name one with --topic") +
                   "; " + topic_list(topics));
}

}  // namespace conicloc::io
