// Built-in calibration tables, the VeloView XML override, and position packets (GPRMC).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "io/input_error.hpp"
#include "io/velodyne_packet.hpp"
#include "io/velodyne_position.hpp"
#include "io/veloview_calibration.hpp"
#include "sensor/builtin_calibration.hpp"
#include "test/temp_path.hpp"

namespace conicloc::io {
namespace {

constexpr double kDeg = M_PI / 180.0;
const std::string kDir = std::string(CONICLOC_SHARED_DATA) + "/velodyne/";

TEST(BuiltinCalibration, EveryModelHasItsLaserCountAndRankedRings) {
  for (const auto model :
       {sensor::SensorModel::VLP16, sensor::SensorModel::PuckLite, sensor::SensorModel::PuckHiRes,
        sensor::SensorModel::HDL32E, sensor::SensorModel::VLP32C}) {
    const auto calibration = sensor::builtin_calibration(model);
    ASSERT_EQ(calibration.ring_count(), velodyne::packet_layout(model).channels);
    std::vector<double> by_ring(calibration.lasers.size());
    for (const auto& laser : calibration.lasers) by_ring[laser.ring] = laser.elevation_rad;
    EXPECT_TRUE(std::is_sorted(by_ring.begin(), by_ring.end()));
    EXPECT_EQ(sensor::parse_sensor_model(sensor::sensor_model_name(model)), model);
  }
}

TEST(BuiltinCalibration, ManualValues) {
  const auto hires = sensor::builtin_calibration(sensor::SensorModel::PuckHiRes);
  EXPECT_NEAR(hires.lasers[0].elevation_rad, -10.0 * kDeg, 1e-12);
  EXPECT_NEAR(hires.lasers[15].elevation_rad, 10.0 * kDeg, 1e-12);
  EXPECT_NEAR(hires.lasers[0].vertical_offset_m, 0.0074, 1e-12);
  const auto hdl = sensor::builtin_calibration(sensor::SensorModel::HDL32E);
  EXPECT_NEAR(hdl.lasers[0].elevation_rad, -30.67 * kDeg, 1e-12);
  EXPECT_NEAR(hdl.lasers[31].elevation_rad, 10.67 * kDeg, 1e-12);
  EXPECT_EQ(hdl.lasers[0].ring, 0);
  EXPECT_EQ(hdl.lasers[31].ring, 31);
  const auto vlp32c = sensor::builtin_calibration(sensor::SensorModel::VLP32C);
  EXPECT_NEAR(vlp32c.lasers[0].elevation_rad, -25.0 * kDeg, 1e-12);
  EXPECT_NEAR(vlp32c.lasers[29].elevation_rad, 15.0 * kDeg, 1e-12);
  // The manual's +1.4° (clockwise) offset is −1.4° in our counter-clockwise azimuth.
  EXPECT_NEAR(vlp32c.lasers[0].azimuth_offset_rad, -1.4 * kDeg, 1e-12);
  EXPECT_NEAR(vlp32c.lasers[1].azimuth_offset_rad, 4.2 * kDeg, 1e-12);
}

TEST(VeloViewCalibration, ReadsTheSharedFilesAndMatchesTheManualAngles) {
  const std::string xml = kDir + "veloview-HDL-32.xml";
  if (!std::filesystem::exists(xml)) GTEST_SKIP() << "shared Velodyne data absent";
  const auto loaded = read_veloview_calibration(xml, sensor::SensorModel::HDL32E);
  const auto builtin = sensor::builtin_calibration(sensor::SensorModel::HDL32E);
  ASSERT_EQ(loaded.calibration.ring_count(), 32);
  for (int k = 0; k < 32; ++k) {
    EXPECT_NEAR(loaded.calibration.lasers[k].elevation_rad, builtin.lasers[k].elevation_rad, 1e-6);
    EXPECT_EQ(loaded.calibration.lasers[k].ring, builtin.lasers[k].ring);
  }
  EXPECT_NEAR(loaded.distance_unit_m, 0.002, 1e-12);
  const auto vlp =
      read_veloview_calibration(kDir + "veloview-VLP-16.xml", sensor::SensorModel::VLP16);
  EXPECT_NEAR(vlp.calibration.lasers[1].elevation_rad, 1.0 * kDeg, 1e-9);
  EXPECT_EQ(vlp.calibration.lasers[1].vertical_offset_m, 0.0);  // VeloView's file has none
}

TEST(VeloViewCalibration, OverridesOffsetsAndRejectsBadFiles) {
  const std::string path = conicloc::test::unique_temp_path("cal.xml").string();
  auto write = [&](const std::string& px_extra, int lasers) {
    std::ofstream out(path);
    out << "<?xml version=\"1.0\"?>\n<boost_serialization><DB><distLSB_>0.2</distLSB_><points_>";
    for (int k = 0; k < lasers; ++k) {
      out << "<item><px><id_>" << k << "</id_><rotCorrection_>0.5</rotCorrection_><vertCorrection_>"
          << (k - 8) << "</vertCorrection_><vertOffsetCorrection_>1.5</vertOffsetCorrection_>"
          << (k == 2 ? px_extra : "") << "</px></item>";
    }
    out << "</points_></DB></boost_serialization>\n";
  };
  write("", 16);
  const auto loaded = read_veloview_calibration(path, sensor::SensorModel::VLP16);
  EXPECT_NEAR(loaded.calibration.lasers[3].elevation_rad, -5 * kDeg, 1e-12);
  EXPECT_NEAR(loaded.calibration.lasers[3].vertical_offset_m, 0.015, 1e-12);
  EXPECT_NEAR(loaded.calibration.lasers[3].azimuth_offset_rad, 0.5 * kDeg, 1e-12);
  EXPECT_EQ(loaded.calibration.lasers[0].ring, 0);
  EXPECT_TRUE(loaded.warnings.empty());

  write("<distCorrection_>12</distCorrection_>", 16);  // modelled: a range offset, cm
  const auto with_distance = read_veloview_calibration(path, sensor::SensorModel::VLP16);
  EXPECT_TRUE(with_distance.warnings.empty());
  EXPECT_NEAR(with_distance.calibration.lasers[2].range_offset_m, 0.12, 1e-12);
  EXPECT_EQ(with_distance.calibration.lasers[3].range_offset_m, 0.0);
  write("<horizOffsetCorrection_>2</horizOffsetCorrection_>", 16);
  EXPECT_EQ(read_veloview_calibration(path, sensor::SensorModel::VLP16).warnings.size(), 1u);
  write("", 12);  // too few lasers
  EXPECT_THROW(read_veloview_calibration(path, sensor::SensorModel::VLP16), InputError);
  {
    std::ofstream out(path);
    out << "<boost_serialization><DB><points_><item><px><id_>0</id_><vertCorrection_>abc"
           "</vertCorrection_></px></item></points_></DB></boost_serialization>";
  }
  try {
    read_veloview_calibration(path, sensor::SensorModel::VLP16);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("vertCorrection_"), std::string::npos);
  }
  std::ofstream(path) << "<not closed";
  EXPECT_THROW(read_veloview_calibration(path, sensor::SensorModel::VLP16), InputError);
  std::filesystem::remove(path);
}

TEST(VeloViewCalibration, WriterRoundTripsThroughTheReader) {
  const std::string path = conicloc::test::unique_temp_path("written.xml").string();
  sensor::LaserCalibration calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  for (int k = 0; k < calibration.ring_count(); ++k) {
    auto& laser = calibration.lasers[k];
    laser.elevation_rad += 0.0123 * kDeg * std::sin(k + 0.5);
    laser.vertical_offset_m += 0.0017 * std::cos(k);
    laser.azimuth_offset_rad = -0.21 * kDeg * std::sin(2.0 * k);
    laser.range_offset_m = 0.0043 * std::cos(3.0 * k + 1.0);
  }
  std::swap(calibration.lasers[3].elevation_rad, calibration.lasers[4].elevation_rad);  // re-rank
  write_veloview_calibration(path, calibration, 0.002);
  const auto loaded = read_veloview_calibration(path, sensor::SensorModel::VLP16);
  EXPECT_TRUE(loaded.warnings.empty());
  EXPECT_NEAR(loaded.distance_unit_m, 0.002, 1e-15);
  ASSERT_EQ(loaded.calibration.ring_count(), calibration.ring_count());
  int rank_3 = 0, rank_4 = 0;
  for (int k = 0; k < calibration.ring_count(); ++k) {
    const auto& a = calibration.lasers[k];
    const auto& b = loaded.calibration.lasers[k];
    // Degrees and centimetres with 17 digits: back to the same value up to one conversion's
    // rounding.
    EXPECT_NEAR(b.elevation_rad, a.elevation_rad, 1e-15);
    EXPECT_NEAR(b.vertical_offset_m, a.vertical_offset_m, 1e-16);
    EXPECT_NEAR(b.azimuth_offset_rad, a.azimuth_offset_rad, 1e-16);
    EXPECT_NEAR(b.range_offset_m, a.range_offset_m, 1e-16);
    rank_3 += calibration.lasers[k].elevation_rad < calibration.lasers[3].elevation_rad;
    rank_4 += calibration.lasers[k].elevation_rad < calibration.lasers[4].elevation_rad;
  }
  EXPECT_EQ(loaded.calibration.lasers[3].ring, rank_3);
  EXPECT_EQ(loaded.calibration.lasers[4].ring, rank_4);
  EXPECT_THROW(write_veloview_calibration("/nonexistent-dir/cal.xml", calibration, 0.002),
               InputError);
  std::filesystem::remove(path);
}

TEST(PositionPacket, ParsesGprmc) {
  const auto fix =
      parse_gprmc("$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6A");
  ASSERT_TRUE(fix.has_value());
  EXPECT_TRUE(fix->valid);
  EXPECT_TRUE(fix->checksum_ok);
  EXPECT_NEAR(fix->utc_time_of_day_s, 12 * 3600 + 35 * 60 + 19, 1e-9);
  EXPECT_NEAR(*fix->latitude_deg, 48 + 7.038 / 60, 1e-9);
  EXPECT_NEAR(*fix->longitude_deg, 11 + 31.0 / 60, 1e-9);
  EXPECT_EQ(*fix->utc_epoch_s, 764426119.0);  // 1994-03-23 12:35:19 UTC
  const auto south_west = parse_gprmc("$GPRMC,000000,V,3000.000,S,07000.000,W,0,0,010120,,*00");
  ASSERT_TRUE(south_west.has_value());
  EXPECT_FALSE(south_west->valid);
  EXPECT_FALSE(south_west->checksum_ok);
  EXPECT_NEAR(*south_west->latitude_deg, -30.0, 1e-12);
  EXPECT_NEAR(*south_west->longitude_deg, -70.0, 1e-12);
  EXPECT_FALSE(parse_gprmc("$GPGGA,123519,4807.038,N").has_value());
}

TEST(PositionPacket, ReadsStampPpsAndSentenceAndPutsTheClockOnUtc) {
  std::vector<std::uint8_t> payload(512, 0);
  velodyne::write_u32(payload.data() + 198, 35 * 60 * 1'000'000u + 19'000'000u);  // 12:35:19
  payload[202] = 2;
  const std::string nmea =
      "$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6A\r\n";
  std::copy(nmea.begin(), nmea.end(), payload.begin() + 206);
  const auto packet = parse_position_packet(payload);
  ASSERT_TRUE(packet.has_value());
  EXPECT_EQ(packet->pps_status, 2);
  EXPECT_STREQ(pps_status_name(packet->pps_status), "locked");
  EXPECT_EQ(packet->nmea, nmea.substr(0, nmea.size() - 2));
  ASSERT_TRUE(utc_hour_start(*packet).has_value());
  EXPECT_EQ(*utc_hour_start(*packet), 764426119.0 - 35 * 60 - 19);
  EXPECT_FALSE(parse_position_packet(std::vector<std::uint8_t>(511, 0)).has_value());
}

}  // namespace
}  // namespace conicloc::io
