// Which topic of a bag is read: the named one, else the only VelodyneScan or PointCloud2 topic;
// every other case is an error that lists the topics and their types.
#include <gtest/gtest.h>

#include "io/bag_topic.hpp"

namespace conicloc::io {
namespace {

const BagTopic kScans{"/velodyne_packets", "velodyne_msgs/msg/VelodyneScan", "cdr",
                      MessageEncoding::Cdr};
const BagTopic kFrontScans{"/front/velodyne_packets", "velodyne_msgs/VelodyneScan", "ros1",
                           MessageEncoding::Ros1};
const BagTopic kPoints{"/velodyne_points", "sensor_msgs/PointCloud2", "ros1",
                       MessageEncoding::Ros1};
const BagTopic kImu{"/imu", "sensor_msgs/msg/Imu", "cdr", MessageEncoding::Cdr};

std::string error_of(const std::vector<BagTopic>& topics, const std::string& requested) {
  try {
    choose_velodyne_topic(topics, requested);
  } catch (const TopicError& e) {
    return e.what();
  }
  return "";
}

TEST(BagTopic, TakesTheOnlyScanTopicOrTheNamedOne) {
  EXPECT_EQ(choose_velodyne_topic({kImu, kScans}, "").name, "/velodyne_packets");
  EXPECT_EQ(choose_velodyne_topic({kScans, kFrontScans}, "/front/velodyne_packets").name,
            "/front/velodyne_packets");
}

TEST(BagTopic, TakesTheOnlyPointCloudTopic) {
  EXPECT_EQ(choose_velodyne_topic({kImu, kPoints}, "").name, "/velodyne_points");
  const std::string both = error_of({kScans, kPoints}, "");
  EXPECT_NE(both.find("2 topics of type"), std::string::npos) << both;
  EXPECT_EQ(choose_velodyne_topic({kScans, kPoints}, "/velodyne_points").type,
            "sensor_msgs/PointCloud2");
}

TEST(BagTopic, AmbiguousOrMissingListsEveryTopic) {
  const std::string two = error_of({kScans, kFrontScans, kImu}, "");
  EXPECT_NE(two.find("2 topics of type velodyne_msgs/VelodyneScan or sensor_msgs/PointCloud2: "
                     "name one with --topic"),
            std::string::npos)
      << two;
  EXPECT_NE(two.find("/front/velodyne_packets  (velodyne_msgs/VelodyneScan, ros1)"),
            std::string::npos)
      << two;
  EXPECT_NE(two.find("/imu  (sensor_msgs/msg/Imu, cdr)"), std::string::npos) << two;
  const std::string none = error_of({kImu}, "");
  EXPECT_NE(none.find("no topic of type velodyne_msgs/VelodyneScan"), std::string::npos) << none;
  const std::string absent = error_of({kScans}, "/points");
  EXPECT_NE(absent.find("no topic /points"), std::string::npos) << absent;
  EXPECT_NE(error_of({}, "").find("the bag has no topics"), std::string::npos);
}

TEST(BagTopic, RefusesAnotherTypeOrAnUnreadableEncoding) {
  const std::string wrong = error_of({kScans, kImu}, "/imu");
  EXPECT_NE(wrong.find("topic /imu holds sensor_msgs/msg/Imu"), std::string::npos) << wrong;
  BagTopic json = kScans;
  json.encoding_name = "json";
  json.encoding.reset();
  EXPECT_NE(error_of({json}, "").find("encoded as 'json'"), std::string::npos);
}

}  // namespace
}  // namespace conicloc::io
