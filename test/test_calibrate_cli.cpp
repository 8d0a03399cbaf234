// `conicloc simulate --calib-*` and `conicloc calibrate` end to end on a short simulated capture:
// the truth files are written, the calibration XML reads back, the report holds the keys.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "io/tum_trajectory.hpp"
#include "io/veloview_calibration.hpp"
#include "sensor/builtin_calibration.hpp"
#include "test/cli_run.hpp"
#include "test/temp_path.hpp"

namespace conicloc::test {
namespace {

namespace fs = std::filesystem;

std::string quoted(const fs::path& path) {
  std::string out = "'";  // appended, not "'" + string: GCC 12 warns falsely (-Wrestrict) there
  out += path.string();
  out += '\'';
  return out;
}

// The number after "key": in `json` from `from` on (the report's keys are unique per object).
double json_number(const std::string& json, const std::string& key, std::size_t from = 0) {
  const auto at = json.find("\"" + key + "\":", from);
  if (at == std::string::npos) return std::nan("");
  return std::stod(json.substr(at + key.size() + 3));
}

TEST(CalibrateCli, SimulatedCaptureGivesXmlAndReportWithEveryKey) {
  const fs::path dir = unique_temp_path("calibrate-cli");
  fs::create_directories(dir);
  const int sim = run_conicloc(
      "simulate --out " + quoted(dir / "run.pcap") + " --truth " + quoted(dir / "truth.tum") +
          " --duration 2.5 --seed 3 --clutter 0 --calib-error-deg 0.1 --calib-offset-error-mm 5 "
          "--calib-azimuth-error-deg 0.1 --calib-truth " +
          quoted(dir / "calib-truth.json") + " --calib-truth-xml " + quoted(dir / "true.xml"),
      dir / "sim.log");
  ASSERT_EQ(sim, 0) << slurp(dir / "sim.log");
  const std::string truth_json = slurp(dir / "calib-truth.json");
  for (const char* key : {"\"calib_error_deg\"", "\"calib_offset_error_mm\":5", "\"seed\":3",
                          "\"elevation_error_deg\"", "\"range_offset_error_m\"", "\"mounting\""}) {
    EXPECT_NE(truth_json.find(key), std::string::npos) << key;
  }
  const auto truth_xml =
      io::read_veloview_calibration((dir / "true.xml").string(), sensor::SensorModel::VLP16);
  const auto nominal = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  double range_offsets = 0.0;
  for (const auto& laser : truth_xml.calibration.lasers)
    range_offsets += std::abs(laser.range_offset_m);
  EXPECT_GT(range_offsets, 0.0);  // the sensor really is off its nominal table

  const auto truth = io::read_tum((dir / "truth.tum").string());
  ASSERT_FALSE(truth.empty());
  const int calibrate = run_conicloc(
      "calibrate --pcap " + quoted(dir / "run.pcap") + " --out " + quoted(dir / "cal.xml") +
          " --report " + quoted(dir / "cal.json") + " --truth " + quoted(dir / "true.xml") +
          " --init " + init_argument(truth.front().pose) +
          " --settle-scans 4 --scans 4 --return-stride 16 --threads 1",
      dir / "calibrate.log");
  ASSERT_EQ(calibrate, 0) << slurp(dir / "calibrate.log");
  const auto written =
      io::read_veloview_calibration((dir / "cal.xml").string(), sensor::SensorModel::VLP16);
  EXPECT_TRUE(written.warnings.empty());
  ASSERT_EQ(written.calibration.ring_count(), nominal.ring_count());
  const std::string report = slurp(dir / "cal.json");
  for (const char* key :
       {"\"lasers\"", "\"laser_id\"", "\"ring\"", "\"elevation_deg\"", "\"elevation_sigma_deg\"",
        "\"vertical_offset_m\"", "\"azimuth_offset_deg\"", "\"range_offset_m\"", "\"observable\"",
        "\"mounting\"", "\"height_m\"", "\"height_sigma_m\"", "\"roll_deg\"", "\"roll_sigma_deg\"",
        "\"pitch_deg\"", "\"pitch_sigma_deg\"", "\"truth\"", "\"elevation_rms_deg\"",
        "\"unmapped_returns\""}) {
    EXPECT_NE(report.find(key), std::string::npos) << key;
  }
  // The capture stays on the ground floor: no scan is left out as climbing.
  EXPECT_NE(report.find("\"climbing_scans\":0,"), std::string::npos);
  // ... over the ground floor's polygon, adjusted: every scan's height is taken above it, and
  // the model's h above the map's floor is reported beside it.
  EXPECT_EQ(json_number(report, "height_floor_scans"), 4.0);
  EXPECT_TRUE(std::isfinite(json_number(report, "height_above_map_floor_m")));
  EXPECT_TRUE(std::isfinite(json_number(report, "height_above_map_floor_sigma_m")));
  // The simulator's 3 cm range noise is read off the residuals as range noise (return_noise.hpp):
  // ~7,000 returns in 10 bins, each bin's σ within ~5%. The surfaces' error left is what the
  // plane adjustment leaves of the map's 2 cm from 4 scans (measured 1.2 cm).
  EXPECT_NEAR(json_number(report, "range_noise_sigma_m"), 0.03, 0.003);
  EXPECT_LT(json_number(report, "surface_error_sigma_m"), 0.02);
  fs::remove_all(dir);
}

TEST(CalibrateCli, TwoSensorsInOneCaptureGiveTheSecondSensorsPose) {
  // `simulate --second-sensor` writes a second VLP-16's packets (192.168.1.202, port 2369) into
  // the capture; `calibrate --second-sensor` finds where it sits on the carrier.
  const fs::path dir = unique_temp_path("calibrate-cli-two");
  fs::create_directories(dir);
  const int sim = run_conicloc(
      "simulate --out " + quoted(dir / "run.pcap") + " --truth " + quoted(dir / "truth.tum") +
          " --duration 3 --seed 5 --clutter 0 --mount-pitch-deg 4 --second-sensor "
          "0.1,-0.2,0.3,2,-3,90 --calib-error-deg 0.05 --calib-truth " +
          quoted(dir / "calib-truth.json") + " --calib-truth-xml " + quoted(dir / "true.xml") +
          " --second-calib-truth-xml " + quoted(dir / "second-true.xml"),
      dir / "sim.log");
  ASSERT_EQ(sim, 0) << slurp(dir / "sim.log");
  // Each sensor's own laser errors: in the JSON (the second's inside "second_sensor") and as XML.
  const std::string truth_json = slurp(dir / "calib-truth.json");
  const auto second_truth = truth_json.find("\"second_sensor\"");
  ASSERT_NE(second_truth, std::string::npos);
  const auto first_lasers = truth_json.rfind("\"lasers\"");
  const auto second_lasers = truth_json.find("\"lasers\"", second_truth);
  ASSERT_NE(second_lasers, std::string::npos);
  EXPECT_LT(second_lasers, first_lasers);  // the first's own array follows the second's object
  const auto first_xml =
      io::read_veloview_calibration((dir / "true.xml").string(), sensor::SensorModel::VLP16);
  const auto second_xml =
      io::read_veloview_calibration((dir / "second-true.xml").string(), sensor::SensorModel::VLP16);
  ASSERT_EQ(second_xml.calibration.ring_count(), 16);
  const auto nominal = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  // The JSON's first laser of the second sensor is the XML's.
  EXPECT_NEAR(json_number(truth_json, "elevation_error_deg", second_lasers),
              (second_xml.calibration.lasers[0].elevation_rad - nominal.lasers[0].elevation_rad) *
                  180.0 / M_PI,
              1e-4);
  double differ = 0.0;
  for (int k = 0; k < 16; ++k) {
    differ += std::abs(second_xml.calibration.lasers[k].elevation_rad -
                       first_xml.calibration.lasers[k].elevation_rad);
  }
  EXPECT_GT(differ, 0.0);  // drawn apart: two sensors, two sets of errors
  const auto truth = io::read_tum((dir / "truth.tum").string());
  ASSERT_FALSE(truth.empty());
  const std::string common = "calibrate --pcap " + quoted(dir / "run.pcap") + " --out " +
                             quoted(dir / "cal.xml") + " --report " + quoted(dir / "cal.json") +
                             " --init " + init_argument(truth.front().pose) +
                             " --init-tilt 0,4 --settle-scans 4 --scans 6 --return-stride 8 "
                             "--threads 1 --sensor 192.168.1.201:2368";
  const int calibrate = run_conicloc(
      common + " --second-sensor 192.168.1.202:2369 --second-init 0.12,-0.18,0.28,1,-2,89",
      dir / "calibrate.log");
  ASSERT_EQ(calibrate, 0) << slurp(dir / "calibrate.log");
  const std::string report = slurp(dir / "cal.json");
  const auto second = report.find("\"second_sensor\"");
  ASSERT_NE(second, std::string::npos) << report;
  for (const char* key : {"\"x_m\"", "\"x_sigma_m\"", "\"roll_sigma_deg\"", "\"yaw_deg\"",
                          "\"observable\"", "\"covariance\"", "\"returns\""}) {
    EXPECT_NE(report.find(key, second), std::string::npos) << key;
  }
  EXPECT_NEAR(json_number(report, "x_m", second), 0.1, 0.01);
  EXPECT_NEAR(json_number(report, "y_m", second), -0.2, 0.01);
  EXPECT_NEAR(json_number(report, "z_m", second), 0.3, 0.03);  // the first's height, 3 s of data
  EXPECT_NEAR(json_number(report, "roll_deg", second), 2.0, 0.3);
  EXPECT_NEAR(json_number(report, "pitch_deg", second), -3.0, 0.3);
  EXPECT_NEAR(json_number(report, "yaw_deg", second), 90.0, 0.3);

  // A second sensor that is the first one is refused, naming the flag.
  EXPECT_NE(run_conicloc(common + " --second-sensor 2368", dir / "same.log"), 0);
  EXPECT_NE(slurp(dir / "same.log").find("--second-sensor"), std::string::npos);
  fs::remove_all(dir);
}

TEST(CalibrateCli, MissingCaptureIsAnError) {
  const fs::path dir = unique_temp_path("calibrate-cli-bad");
  fs::create_directories(dir);
  EXPECT_NE(run_conicloc("calibrate --pcap " + quoted(dir / "none.pcap") + " --out " +
                             quoted(dir / "cal.xml"),
                         dir / "log"),
            0);
  EXPECT_NE(slurp(dir / "log").find("none.pcap"), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace conicloc::test
