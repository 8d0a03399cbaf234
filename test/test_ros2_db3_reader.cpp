// ROS 2 .db3 bags made with the SQLite API: the topic choice, the message order, a broken message
// named by its row, a bag folder, and databases that are not bags.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <filesystem>

#include "io/input_error.hpp"
#include "io/open_capture.hpp"
#include "test/bag_bytes.hpp"
#include "test/temp_path.hpp"

namespace conicloc::io {
namespace {

using test::Bytes;

void exec(sqlite3* db, const std::string& sql) {
  ASSERT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr), SQLITE_OK) << sql;
}

void insert(sqlite3* db, int id, int topic, std::int64_t timestamp, const Bytes& data) {
  sqlite3_stmt* statement = nullptr;
  sqlite3_prepare_v2(db, "INSERT INTO messages VALUES (?, ?, ?, ?)", -1, &statement, nullptr);
  sqlite3_bind_int(statement, 1, id);
  sqlite3_bind_int(statement, 2, topic);
  sqlite3_bind_int64(statement, 3, timestamp);
  sqlite3_bind_blob(statement, 4, data.data(), static_cast<int>(data.size()), SQLITE_TRANSIENT);
  EXPECT_EQ(sqlite3_step(statement), SQLITE_DONE);
  sqlite3_finalize(statement);
}

// Two VelodyneScan topics; /front gets messages of 1 and 2 packets (stored out of time order),
// /rear one message of 3 packets and a cut one.
std::string make_bag(const std::filesystem::path& path) {
  std::filesystem::remove(path);
  sqlite3* db = nullptr;
  sqlite3_open(path.c_str(), &db);
  exec(db,
       "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, "
       "serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);"
       "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, timestamp "
       "INTEGER NOT NULL, data BLOB NOT NULL);"
       "INSERT INTO topics VALUES (1, '/front', 'velodyne_msgs/msg/VelodyneScan', 'cdr', '');"
       "INSERT INTO topics VALUES (2, '/rear', 'velodyne_msgs/msg/VelodyneScan', 'cdr', '');");
  insert(db, 1, 1, 200, test::cdr_velodyne_scan(2));
  insert(db, 2, 1, 100, test::cdr_velodyne_scan(1));
  insert(db, 3, 2, 100, test::cdr_velodyne_scan(3));
  Bytes cut = test::cdr_velodyne_scan(2);
  cut.resize(cut.size() - 30);
  insert(db, 4, 2, 50, cut);
  sqlite3_close(db);
  return path.string();
}

std::vector<int> packet_marks(CaptureSource& capture) {
  std::vector<int> marks;
  while (auto datagram = capture.next()) marks.push_back(datagram->payload[0]);
  return marks;
}

TEST(Ros2Db3Reader, TwoScanTopicsNeedATopicAndMessagesComeInTimeOrder) {
  const std::string path = make_bag(test::unique_temp_path("two.db3"));
  try {
    open_capture(path);
    FAIL() << "an ambiguous bag was opened";
  } catch (const InputError& e) {
    EXPECT_EQ(e.place(), "topics");
    EXPECT_NE(std::string(e.what()).find("/rear  (velodyne_msgs/msg/VelodyneScan, cdr)"),
              std::string::npos);
  }
  const auto front = open_capture(path, {.topic = "/front"});
  EXPECT_EQ(front->format(), "ROS 2 db3");
  EXPECT_EQ(packet_marks(*front), (std::vector<int>{0, 0, 1}));

  const auto rear = open_capture(path, {.topic = "/rear"});
  EXPECT_EQ(packet_marks(*rear), (std::vector<int>{0, 1, 2}));
  ASSERT_EQ(rear->counts().problems.size(), 1u);
  EXPECT_EQ(rear->counts().problems[0].rfind("messages row id 4: ", 0), 0u)
      << rear->counts().problems[0];
  std::filesystem::remove(path);
}

TEST(Ros2Db3Reader, OpensABagFolderAndRefusesOtherDatabases) {
  const auto folder = test::unique_temp_path("bag_folder");
  std::filesystem::create_directories(folder);
  make_bag(folder / "bag_0.db3");
  EXPECT_EQ(packet_marks(*open_capture(folder.string(), {.topic = "/front"})).size(), 3u);
  make_bag(folder / "bag_1.db3");
  EXPECT_THROW(open_capture(folder.string(), {.topic = "/front"}), InputError);
  std::filesystem::remove_all(folder);

  const auto other = test::unique_temp_path("other.db3");
  sqlite3* db = nullptr;
  sqlite3_open(other.c_str(), &db);
  exec(db, "CREATE TABLE things(id INTEGER);");
  sqlite3_close(db);
  try {
    open_capture(other.string());
    FAIL() << "a database without rosbag2's tables was opened";
  } catch (const InputError& e) {
    EXPECT_EQ(e.place(), "table topics");
  }
  std::filesystem::remove(other);
}

}  // namespace
}  // namespace conicloc::io
