// CDR reading and the VelodyneScan message in both serialisations, on hand-built buffers whose
// every offset is known.
#include <gtest/gtest.h>

#include "io/cdr_reader.hpp"
#include "io/velodyne_scan_msg.hpp"
#include "test/bag_bytes.hpp"

namespace conicloc::io {
namespace {

using test::Bytes;

TEST(CdrReader, AlignsFromTheEndOfTheEncapsulationHeader) {
  // u8 7, 3 bytes padding, u32 0x01020304, string "ab" (length 3 with the NUL), i32 -2.
  const Bytes message = {0x00, 0x01, 0x00, 0x00, 7,   0,   0, 0, 4,    3,    2,    1,
                         3,    0,    0,    0,    'a', 'b', 0, 0, 0xFE, 0xFF, 0xFF, 0xFF};
  CdrReader cdr(message);
  EXPECT_TRUE(cdr.little_endian());
  EXPECT_EQ(cdr.u8(), 7);
  EXPECT_EQ(cdr.u32(), 0x01020304u);
  EXPECT_EQ(cdr.offset(), 12u);
  EXPECT_EQ(cdr.string(), "ab");
  EXPECT_EQ(cdr.i32(), -2);
  EXPECT_EQ(cdr.offset(), message.size());
  EXPECT_THROW(cdr.u8(), CdrError);
}

TEST(CdrReader, ReadsBigEndian) {
  const Bytes message = {0x00, 0x00, 0x00, 0x00, 0x01, 0x02, 0x03, 0x04};
  CdrReader cdr(message);
  EXPECT_FALSE(cdr.little_endian());
  EXPECT_EQ(cdr.u32(), 0x01020304u);
}

TEST(CdrReader, RefusesUnknownEncapsulationAndBadStrings) {
  EXPECT_THROW(CdrReader(Bytes{0x00, 0x07, 0, 0}), CdrError);  // XCDR2, not plain CDR
  EXPECT_THROW(CdrReader(Bytes{0x00, 0x01}), CdrError);
  const Bytes no_nul = {0x00, 0x01, 0, 0, 2, 0, 0, 0, 'a', 'b'};
  CdrReader cdr(no_nul);
  try {
    cdr.string();
    FAIL() << "a string without its NUL was read";
  } catch (const CdrError& e) {
    EXPECT_NE(std::string(e.what()).find("offset 4"), std::string::npos) << e.what();
  }
}

TEST(VelodyneScanMsg, DecodesCdrWithPacketAlignment) {
  const Bytes message = test::cdr_velodyne_scan(3);
  const auto scan = decode_velodyne_scan(message, MessageEncoding::Cdr);
  EXPECT_EQ(scan.frame_id, "velodyne");
  EXPECT_DOUBLE_EQ(scan.stamp_s, 100.000000005);
  ASSERT_EQ(scan.packets.size(), 3u);
  // "velodyne\0" ends at 25, the count is aligned to 28; packet 0: stamp 32, data 40..1246;
  // packet 1's stamp is aligned from 1246 to 1248, its data at 1256.
  EXPECT_EQ(scan.packets[0].data.data(), message.data() + 40);
  EXPECT_EQ(scan.packets[1].data.data(), message.data() + 1256);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(scan.packets[i].data.size(), 1206u);
    EXPECT_EQ(scan.packets[i].data[0], i);
    EXPECT_DOUBLE_EQ(scan.packets[i].stamp_s, 100.0 + 0.001 * static_cast<double>(i));
  }
}

TEST(VelodyneScanMsg, DecodesRos1) {
  const Bytes message = test::ros1_velodyne_scan(2);
  const auto scan = decode_velodyne_scan(message, MessageEncoding::Ros1);
  EXPECT_EQ(scan.frame_id, "velodyne");
  ASSERT_EQ(scan.packets.size(), 2u);
  EXPECT_EQ(scan.packets[1].data.data(), message.data() + 24 + 4 + 8 + 1206 + 8);
  EXPECT_DOUBLE_EQ(scan.packets[1].stamp_s, 100.001);
}

TEST(VelodyneScanMsg, CutOrInflatedMessagesThrow) {
  Bytes cut = test::cdr_velodyne_scan(2);
  cut.resize(cut.size() - 100);
  EXPECT_THROW(decode_velodyne_scan(cut, MessageEncoding::Cdr), MessageError);
  Bytes ros1 = test::ros1_velodyne_scan(2);
  ros1.resize(ros1.size() - 1);
  EXPECT_THROW(decode_velodyne_scan(ros1, MessageEncoding::Ros1), MessageError);
  // A count of 4 billion packets in a message of two: refused before anything is reserved.
  Bytes inflated = test::ros1_velodyne_scan(2);
  for (int i = 0; i < 4; ++i) inflated[24 + i] = 0xFF;
  try {
    decode_velodyne_scan(inflated, MessageEncoding::Ros1);
    FAIL() << "an inflated packet count was accepted";
  } catch (const MessageError& e) {
    EXPECT_NE(std::string(e.what()).find("offset 24"), std::string::npos) << e.what();
  }
  // The ROS 1 serialisation read as CDR is not a VelodyneScan.
  EXPECT_THROW(decode_velodyne_scan(test::ros1_velodyne_scan(1), MessageEncoding::Cdr),
               MessageError);
}

TEST(VelodyneScanMsg, KnowsBothTypeNames) {
  EXPECT_TRUE(is_velodyne_scan_type("velodyne_msgs/VelodyneScan"));
  EXPECT_TRUE(is_velodyne_scan_type("velodyne_msgs/msg/VelodyneScan"));
  EXPECT_FALSE(is_velodyne_scan_type("sensor_msgs/msg/PointCloud2"));
}

}  // namespace
}  // namespace conicloc::io
