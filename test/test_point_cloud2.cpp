// sensor_msgs/PointCloud2 in both serialisations on hand-built bytes, and one cloud as one scan:
// rings from the ring field or from the elevation, azimuth and range from the point, times from
// the time field; NaN points skipped; malformed clouds refused, and skipped by name in a bag.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "io/cloud_scan.hpp"
#include "io/input_error.hpp"
#include "io/point_cloud2_msg.hpp"
#include "io/scan_source.hpp"
#include "sensor/builtin_calibration.hpp"
#include "test/bag_bytes.hpp"
#include "test/temp_path.hpp"

namespace conicloc::io {
namespace {

using test::append;
using test::Bytes;

struct Field {
  std::string name;
  std::uint32_t offset;
  std::uint8_t datatype;
  std::uint32_t count = 1;
};

// The driver's PointXYZIRT layout (PCL-aligned): x y z at 0, 4, 8, intensity at 16, ring at 20,
// time at 24, 32 bytes a point.
const std::vector<Field> kXyzirt = {{"x", 0, 7},          {"y", 4, 7},     {"z", 8, 7},
                                    {"intensity", 16, 7}, {"ring", 20, 4}, {"time", 24, 7}};
const std::vector<Field> kXyzit = {
    {"x", 0, 7}, {"y", 4, 7}, {"z", 8, 7}, {"intensity", 16, 7}, {"time", 24, 7}};
constexpr std::uint32_t kPointStep = 32;

struct Point {
  float x, y, z, intensity;
  std::uint16_t ring;
  float time;
};

Bytes point_bytes(const std::vector<Point>& points) {
  Bytes data(points.size() * kPointStep, 0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::uint8_t* p = data.data() + i * kPointStep;
    std::memcpy(p + 0, &points[i].x, 4);
    std::memcpy(p + 4, &points[i].y, 4);
    std::memcpy(p + 8, &points[i].z, 4);
    std::memcpy(p + 16, &points[i].intensity, 4);
    std::memcpy(p + 20, &points[i].ring, 2);
    std::memcpy(p + 24, &points[i].time, 4);
  }
  return data;
}

struct Cloud {
  std::vector<Field> fields = kXyzirt;
  std::vector<Point> points;
  std::uint32_t point_step = kPointStep;
  std::size_t data_bytes_cut = 0;  ///< bytes taken off the end of data
  bool big_endian = false;         ///< data written big-endian, is_bigendian set
};

// The point bytes of `cloud`, each field byte-swapped when the cloud is big-endian.
Bytes cloud_data(const Cloud& cloud) {
  Bytes data = point_bytes(cloud.points);
  // (offset, size) of each field of the layout.
  const std::pair<std::size_t, std::size_t> fields[] = {{0, 4},  {4, 4},  {8, 4},
                                                        {16, 4}, {20, 2}, {24, 4}};
  if (cloud.big_endian) {
    for (std::size_t at = 0; at < data.size(); at += kPointStep) {
      for (const auto& [offset, size] : fields) {
        const auto first = data.begin() + static_cast<std::ptrdiff_t>(at + offset);
        std::reverse(first, first + static_cast<std::ptrdiff_t>(size));
      }
    }
  }
  data.resize(data.size() - cloud.data_bytes_cut);
  return data;
}

// ROS 1: little-endian, unaligned, strings without NUL. Stamp 100.5 s.
Bytes ros1_cloud(const Cloud& cloud) {
  Bytes out;
  test::put_le32(out, 7);  // seq
  test::put_le32(out, 100);
  test::put_le32(out, 500000000);
  test::put_le32(out, 8);
  test::put_text(out, "velodyne");
  test::put_le32(out, 1);  // height
  test::put_le32(out, static_cast<std::uint32_t>(cloud.points.size()));
  test::put_le32(out, static_cast<std::uint32_t>(cloud.fields.size()));
  for (const auto& field : cloud.fields) {
    test::put_le32(out, static_cast<std::uint32_t>(field.name.size()));
    test::put_text(out, field.name);
    test::put_le32(out, field.offset);
    out.push_back(field.datatype);
    test::put_le32(out, field.count);
  }
  out.push_back(cloud.big_endian ? 1 : 0);  // is_bigendian
  test::put_le32(out, cloud.point_step);
  test::put_le32(out, static_cast<std::uint32_t>(cloud.points.size() * cloud.point_step));
  const Bytes data = cloud_data(cloud);
  test::put_le32(out, static_cast<std::uint32_t>(data.size()));
  append(out, data);
  out.push_back(1);  // is_dense
  return out;
}

// CDR little-endian: primitives aligned to their size from byte 4, strings with their NUL.
class CdrWriter {
 public:
  void u32(std::uint32_t v) {
    while ((out.size() - 4) % 4) out.push_back(0);
    test::put_le32(out, v);
  }
  void u8(std::uint8_t v) { out.push_back(v); }
  void string(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size() + 1));
    test::put_text(out, s);
    out.push_back(0);
  }
  Bytes out = {0x00, 0x01, 0x00, 0x00};
};

Bytes cdr_cloud(const Cloud& cloud) {
  CdrWriter cdr;
  cdr.u32(100);
  cdr.u32(500000000);
  cdr.string("velodyne");
  cdr.u32(1);
  cdr.u32(static_cast<std::uint32_t>(cloud.points.size()));
  cdr.u32(static_cast<std::uint32_t>(cloud.fields.size()));
  for (const auto& field : cloud.fields) {
    cdr.string(field.name);
    cdr.u32(field.offset);
    cdr.u8(field.datatype);
    cdr.u32(field.count);
  }
  cdr.u8(cloud.big_endian ? 1 : 0);
  cdr.u32(cloud.point_step);
  cdr.u32(static_cast<std::uint32_t>(cloud.points.size() * cloud.point_step));
  const Bytes data = cloud_data(cloud);
  cdr.u32(static_cast<std::uint32_t>(data.size()));
  append(cdr.out, data);
  cdr.u8(1);
  return cdr.out;
}

// A point of the laser of rank `ring` of `calibration` at `azimuth_rad` and `range_m` from its
// apex, `time_s` after the stamp.
Point laser_point(const sensor::LaserCalibration& calibration, int ring, double azimuth_rad,
                  double range_m, float time_s) {
  for (const auto& laser : calibration.lasers) {
    if (laser.ring != ring) continue;
    const double horizontal = range_m * std::cos(laser.elevation_rad);
    return {static_cast<float>(horizontal * std::cos(azimuth_rad)),
            static_cast<float>(horizontal * std::sin(azimuth_rad)),
            static_cast<float>(laser.vertical_offset_m + range_m * std::sin(laser.elevation_rad)),
            42.0f,
            static_cast<std::uint16_t>(ring),
            time_s};
  }
  return {};
}

std::string error_of(const Bytes& message, MessageEncoding encoding) {
  try {
    decode_point_cloud2(message, encoding);
  } catch (const MessageError& e) {
    return e.what();
  }
  return "";
}

TEST(PointCloud2Msg, DecodesBothSerialisations) {
  Cloud cloud;
  cloud.points = std::vector<Point>{{1, 2, 3, 10, 5, 0.01f}, {4, 5, 6, 20, 6, 0.02f}};
  for (const auto& [message, encoding] : {std::pair{ros1_cloud(cloud), MessageEncoding::Ros1},
                                          std::pair{cdr_cloud(cloud), MessageEncoding::Cdr}}) {
    const PointCloud2View view = decode_point_cloud2(message, encoding);
    EXPECT_DOUBLE_EQ(view.stamp_s, 100.5);
    EXPECT_EQ(view.frame_id, "velodyne");
    EXPECT_EQ(view.height, 1u);
    EXPECT_EQ(view.width, 2u);
    EXPECT_EQ(view.point_step, kPointStep);
    EXPECT_EQ(view.row_step, 2 * kPointStep);
    EXPECT_TRUE(view.is_dense);
    ASSERT_EQ(view.fields.size(), 6u);
    EXPECT_EQ(view.fields[4].name, "ring");
    EXPECT_EQ(view.fields[4].offset, 20u);
    EXPECT_EQ(view.fields[4].datatype, PointFieldType::Uint16);
    EXPECT_EQ(view.fields[5].datatype, PointFieldType::Float32);
    EXPECT_DOUBLE_EQ(view.value(*view.field("y"), 1), 5.0);
    EXPECT_DOUBLE_EQ(view.value(*view.field("ring"), 1), 6.0);
    EXPECT_FLOAT_EQ(static_cast<float>(view.value(*view.field("time"), 0)), 0.01f);
  }
}

TEST(PointCloud2Msg, ReadsBigEndianPointData) {
  Cloud cloud;
  cloud.big_endian = true;
  cloud.points = std::vector<Point>{{1.5f, -2.25f, 3, 10, 258, 0.01f}};
  for (const auto& [message, encoding] : {std::pair{ros1_cloud(cloud), MessageEncoding::Ros1},
                                          std::pair{cdr_cloud(cloud), MessageEncoding::Cdr}}) {
    const PointCloud2View view = decode_point_cloud2(message, encoding);
    EXPECT_TRUE(view.is_bigendian);
    EXPECT_DOUBLE_EQ(view.value(*view.field("x"), 0), 1.5);
    EXPECT_DOUBLE_EQ(view.value(*view.field("y"), 0), -2.25);
    EXPECT_DOUBLE_EQ(view.value(*view.field("ring"), 0), 258.0);  // 0x0102, both bytes matter
    EXPECT_FLOAT_EQ(static_cast<float>(view.value(*view.field("time"), 0)), 0.01f);
  }
}

TEST(PointCloud2Msg, RefusesCloudsThatDoNotFitTheirBytes) {
  Cloud cloud;
  cloud.points = std::vector<Point>{{1, 2, 3, 10, 5, 0.01f}, {4, 5, 6, 20, 6, 0.02f}};
  Cloud cut = cloud;
  cut.data_bytes_cut = 8;  // the last point runs past the data
  for (const auto encoding : {MessageEncoding::Ros1, MessageEncoding::Cdr}) {
    const auto& make = encoding == MessageEncoding::Ros1 ? ros1_cloud : cdr_cloud;
    const std::string short_data = error_of(make(cut), encoding);
    EXPECT_NE(short_data.find("needs 64 bytes of data, has 56"), std::string::npos) << short_data;
    Cloud unknown = cloud;
    unknown.fields[5].datatype = 9;
    const std::string datatype = error_of(make(unknown), encoding);
    EXPECT_NE(datatype.find("field 'time' has unknown datatype 9"), std::string::npos) << datatype;
    Cloud outside = cloud;
    outside.fields[5].offset = 30;  // a float at 30..34 in a 32-byte point
    const std::string beyond = error_of(make(outside), encoding);
    EXPECT_NE(beyond.find("field 'time' ends at byte 34, beyond point_step 32"), std::string::npos)
        << beyond;
    outside.fields[5].count = 0;  // no values, but one named at its offset
    EXPECT_EQ(error_of(make(outside), encoding), beyond);
    Bytes truncated = make(cloud);
    truncated.resize(truncated.size() / 2);
    EXPECT_NE(error_of(truncated, encoding), "");
  }
}

TEST(CloudScan, MapsRingAzimuthRangeAndTimeFromTheFields) {
  const auto calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  Cloud cloud;
  cloud.points = std::vector<Point>{laser_point(calibration, 3, 1.5, 5.0, 0.002f),
                                    laser_point(calibration, 3, 0.5, 4.0, 0.001f),
                                    laser_point(calibration, 15, 5.5, 7.0, 0.090f),
                                    {NAN, 1, 1, 10, 2, 0.05f},
                                    {1, 1, 1, 10, 2, NAN},
                                    {0, 0, 0, 10, 2, 0.05f}};
  for (const auto& [message, encoding] : {std::pair{ros1_cloud(cloud), MessageEncoding::Ros1},
                                          std::pair{cdr_cloud(cloud), MessageEncoding::Cdr}}) {
    const auto scan = cloud_to_scan(decode_point_cloud2(message, encoding), calibration, 100.0);
    ASSERT_EQ(scan.rings.size(), 16u);
    EXPECT_EQ(scan.valid_returns(), 3u);  // the NaNs and the placeholder at the origin skipped
    EXPECT_TRUE(scan.rings[2].returns.empty());
    const auto& ring3 = scan.rings[3];
    EXPECT_EQ(ring3.ring, 3);
    ASSERT_EQ(ring3.returns.size(), 2u);
    // Sorted by azimuth; times are stamp + time − origin.
    EXPECT_NEAR(ring3.returns[0].azimuth_rad, 0.5, 1e-6);
    EXPECT_NEAR(ring3.returns[0].range_m, 4.0, 1e-5);
    EXPECT_NEAR(ring3.returns[0].time_s, 0.501, 1e-6);
    EXPECT_EQ(ring3.returns[0].intensity, 42);
    EXPECT_NEAR(ring3.returns[1].azimuth_rad, 1.5, 1e-6);
    ASSERT_EQ(scan.rings[15].returns.size(), 1u);
    EXPECT_NEAR(scan.rings[15].returns[0].azimuth_rad, 5.5, 1e-6);  // in [0, 2π)
    EXPECT_NEAR(scan.start_time_s, 0.501, 1e-6);
    EXPECT_NEAR(scan.end_time_s, 0.590, 1e-6);
    EXPECT_TRUE(scan.partial);  // three returns leave most of the turn empty
  }
}

TEST(CloudScan, WithoutARingFieldTheElevationPicksTheLaser) {
  // Lasers with vertical offsets: the elevation is measured from each laser's own apex.
  sensor::LaserCalibration calibration;
  calibration.lasers = {{-0.10, 0.02, 0.0, 0}, {0.00, 0.01, 0.0, 1}, {0.10, -0.01, 0.0, 2}};
  Cloud cloud;
  cloud.fields = kXyzit;
  for (int ring = 0; ring < 3; ++ring) {
    for (int i = 0; i < 90; ++i) {
      cloud.points.push_back(laser_point(calibration, ring, i * 2.0 * M_PI / 90, 3.0 + ring, 0));
    }
  }
  const auto scan = cloud_to_scan(decode_point_cloud2(ros1_cloud(cloud), MessageEncoding::Ros1),
                                  calibration, 100.5);
  for (int ring = 0; ring < 3; ++ring) {
    const auto& returns = scan.rings[static_cast<std::size_t>(ring)].returns;
    ASSERT_EQ(returns.size(), 90u) << "ring " << ring;
    for (const auto& ret : returns) EXPECT_NEAR(ret.range_m, 3.0 + ring, 1e-5);  // from the apex
    EXPECT_NEAR(returns[45].azimuth_rad, M_PI, 1e-6);
  }
  EXPECT_FALSE(scan.partial);  // a return every 4° all round
}

TEST(CloudScan, RefusesARingTheSensorDoesNotHave) {
  const auto calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  Cloud cloud;
  cloud.points = std::vector<Point>{{1, 2, 3, 10, 16, 0.0f}};
  EXPECT_THROW(
      cloud_to_scan(decode_point_cloud2(cdr_cloud(cloud), MessageEncoding::Cdr), calibration, 0.0),
      MessageError);
}

TEST(CloudScanSource, SkipsAMalformedCloudOfABagAndNamesIt) {
  const auto calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  Cloud good;
  good.points = std::vector<Point>{laser_point(calibration, 1, 1.0, 5.0, 0.0f)};
  Cloud bad = good;
  bad.point_step = 40;  // beyond the data
  Bytes file = test::ros1_start();
  append(file, test::ros1_connection(0, "/velodyne_points", "sensor_msgs/PointCloud2"));
  const std::size_t bad_record = file.size();
  append(file, test::ros1_message(0, ros1_cloud(bad)));
  append(file, test::ros1_message(0, ros1_cloud(good)));
  const std::string path = test::unique_temp_path("clouds.bag").string();
  test::write_bytes(path, file);

  const auto source = open_scan_source(path, calibration);
  EXPECT_EQ(source->stream(), nullptr);
  const auto scan = source->next();
  ASSERT_TRUE(scan);
  EXPECT_EQ(scan->valid_returns(), 1u);
  EXPECT_EQ(scan->rings[1].returns.size(), 1u);
  EXPECT_EQ(source->utc_offset_s(), std::optional<double>(100.5));
  EXPECT_FALSE(source->next());
  ASSERT_EQ(source->counts().problems.size(), 1u);
  EXPECT_EQ(source->counts().bad_messages, 1u);
  const std::string& problem = source->counts().problems[0];
  EXPECT_EQ(problem.rfind("record at byte " + std::to_string(bad_record), 0), 0u) << problem;
  EXPECT_NE(problem.find("needs 40 bytes of data, has 32"), std::string::npos) << problem;
  // The packet path refuses the topic, naming it.
  try {
    open_capture(path);
    FAIL() << "a topic of point clouds was opened as packets";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/velodyne_points holds point clouds"), std::string::npos)
        << e.what();
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace conicloc::io
