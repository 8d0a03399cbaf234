// The map options on every command that loads a map: the example building written in millimetres
// is simulated and localized with --unit-scale 0.001 exactly like the metric one, and `localize`
// refuses it without, naming the file and the --unit-scale to use.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "io/tum_trajectory.hpp"
#include "test/cli_run.hpp"
#include "test/temp_path.hpp"

namespace {

namespace fs = std::filesystem;
using conicloc::test::run_conicloc;
using conicloc::test::slurp;

// Every coordinate of the model (gml:posList, gml:pos, the envelope's corners) times `factor`.
std::string scale_coordinates(const std::string& gml, double factor) {
  static const std::regex element(
      R"((<gml:(?:posList|pos|lowerCorner|upperCorner)\b[^>]*>)([^<]*)(<))");
  std::string out;
  auto begin = std::sregex_iterator(gml.begin(), gml.end(), element);
  std::size_t last = 0;
  for (auto it = begin; it != std::sregex_iterator(); ++it) {
    const auto& match = *it;
    out += gml.substr(last, static_cast<std::size_t>(match.position(0)) - last);
    std::istringstream numbers(match[2].str());
    std::ostringstream scaled;
    scaled.precision(17);
    double value = 0.0;
    for (bool first = true; numbers >> value; first = false) {
      scaled << (first ? "" : " ") << value * factor;
    }
    out += match[1].str() + scaled.str() + match[3].str();
    last = static_cast<std::size_t>(match.position(0) + match.length(0));
  }
  return out + gml.substr(last);
}

class MapUnitsCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = conicloc::test::unique_temp_path("map_units_cli");
    fs::create_directories(dir_);
    const std::string metric = slurp(CONICLOC_EXAMPLE_MAP);
    std::ofstream(dir_ / "building_mm.gml") << scale_coordinates(metric, 1000.0);
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  static std::string simulate(const std::string& map_arguments, const std::string& name) {
    return "simulate " + map_arguments + " --duration 2 --seed 5 --threads 2 --out " +
           (dir_ / (name + ".pcap")).string() + " --truth " + (dir_ / (name + ".tum")).string();
  }
  static std::string mm_map() { return (dir_ / "building_mm.gml").string(); }

  static inline fs::path dir_;
};

TEST_F(MapUnitsCli, MillimetreCopyScalesEveryCoordinate) {
  const std::string mm = slurp(dir_ / "building_mm.gml");
  EXPECT_NE(mm.find("<gml:upperCorner>18000 10000 6200</gml:upperCorner>"), std::string::npos);
  EXPECT_EQ(mm.find("<gml:upperCorner>18 10 6.2</gml:upperCorner>"), std::string::npos);
}

TEST_F(MapUnitsCli, MillimetreMapWithUnitScaleSimulatesAndLocalizesLikeTheMetricMap) {
  ASSERT_EQ(
      run_conicloc(simulate("--map " + std::string(CONICLOC_EXAMPLE_MAP), "m"), dir_ / "sim_m.log"),
      0)
      << slurp(dir_ / "sim_m.log");
  ASSERT_EQ(run_conicloc(simulate("--map " + mm_map() + " --unit-scale 0.001", "mm"),
                         dir_ / "sim_mm.log"),
            0)
      << slurp(dir_ / "sim_mm.log");
  const auto truth_m = conicloc::io::read_tum((dir_ / "m.tum").string());
  const auto truth_mm = conicloc::io::read_tum((dir_ / "mm.tum").string());
  ASSERT_GT(truth_m.size(), 10u);
  ASSERT_EQ(truth_m.size(), truth_mm.size());
  for (std::size_t k = 0; k < truth_m.size(); ++k) {
    EXPECT_NEAR((truth_m[k].pose.translation() - truth_mm[k].pose.translation()).norm(), 0.0, 1e-6);
  }

  const std::string init = conicloc::test::init_argument(truth_m.front().pose);
  const std::string common = " --init " + init +
                             " --init-sigma 0.05,0.05,1 --seed 3 --threads 1 --init-particles 200 "
                             "--min-particles 100";
  ASSERT_EQ(run_conicloc("localize --map " + std::string(CONICLOC_EXAMPLE_MAP) + " --pcap " +
                             (dir_ / "m.pcap").string() + " --out " +
                             (dir_ / "est_m.tum").string() + common,
                         dir_ / "loc_m.log"),
            0)
      << slurp(dir_ / "loc_m.log");
  ASSERT_EQ(run_conicloc("localize --map " + mm_map() + " --unit-scale 0.001 --pcap " +
                             (dir_ / "mm.pcap").string() + " --out " +
                             (dir_ / "est_mm.tum").string() + common,
                         dir_ / "loc_mm.log"),
            0)
      << slurp(dir_ / "loc_mm.log");
  const auto est_m = conicloc::io::read_tum((dir_ / "est_m.tum").string());
  const auto est_mm = conicloc::io::read_tum((dir_ / "est_mm.tum").string());
  ASSERT_GT(est_m.size(), 10u);
  ASSERT_EQ(est_m.size(), est_mm.size());
  for (std::size_t k = 0; k < est_m.size(); ++k) {
    EXPECT_NEAR(est_m[k].time_s, est_mm[k].time_s, 1e-6);
    EXPECT_NEAR((est_m[k].pose.translation() - est_mm[k].pose.translation()).norm(), 0.0, 0.01)
        << "scan " << k;
  }
}

TEST_F(MapUnitsCli, LocalizeRefusesTheMillimetreMapWithoutUnitScaleAndSaysWhichToUse) {
  const fs::path log = dir_ / "refused.log";
  const int code =
      run_conicloc("localize --map " + mm_map() + " --pcap " + std::string(CONICLOC_EXAMPLE_MAP) +
                       " --out " + (dir_ / "refused.tum").string(),
                   log);
  const std::string text = slurp(log);
  EXPECT_NE(code, 0) << text;
  EXPECT_NE(text.find(mm_map()), std::string::npos) << text;
  EXPECT_NE(text.find("3000 m high"), std::string::npos) << text;
  EXPECT_NE(text.find("--unit-scale 0.001"), std::string::npos) << text;
  EXPECT_NE(text.find("--trust-units"), std::string::npos) << text;
  EXPECT_FALSE(fs::exists(dir_ / "refused.tum"));

  // --trust-units: the map is taken as it is, and the run gets as far as the (bad) capture.
  const fs::path trusted = dir_ / "trusted.log";
  EXPECT_NE(run_conicloc("localize --trust-units --map " + mm_map() + " --pcap " +
                             std::string(CONICLOC_EXAMPLE_MAP) + " --out " +
                             (dir_ / "trusted.tum").string(),
                         trusted),
            0);
  EXPECT_EQ(slurp(trusted).find("implausible sizes for a building"), std::string::npos)
      << slurp(trusted);
  EXPECT_NE(slurp(trusted).find("not a readable pcap/pcapng capture"), std::string::npos)
      << slurp(trusted);
}

TEST_F(MapUnitsCli, MapInfoAndPredictAndMapExportReadTheMillimetreMapInMetres) {
  ASSERT_EQ(run_conicloc("map-info --json --unit-scale 0.001 " + mm_map(), dir_ / "info.json"), 0)
      << slurp(dir_ / "info.json");
  EXPECT_NE(slurp(dir_ / "info.json").find("\"bbox_max\":[18"), std::string::npos)
      << slurp(dir_ / "info.json");
  ASSERT_EQ(
      run_conicloc("predict --map " + mm_map() + " --unit-scale 0.001 --pose 3,2,0.8,0 --csv " +
                       (dir_ / "mm.csv").string(),
                   dir_ / "predict_mm.log"),
      0)
      << slurp(dir_ / "predict_mm.log");
  ASSERT_EQ(run_conicloc("predict --map " + std::string(CONICLOC_EXAMPLE_MAP) +
                             " --pose 3,2,0.8,0 --csv " + (dir_ / "m.csv").string(),
                         dir_ / "predict_m.log"),
            0);
  const auto range_m = conicloc::test::csv_column(dir_ / "m.csv", "range_m");
  const auto range_mm = conicloc::test::csv_column(dir_ / "mm.csv", "range_m");
  ASSERT_GT(range_m.size(), 1000u);
  ASSERT_EQ(range_m.size(), range_mm.size());
  for (std::size_t k = 0; k < range_m.size(); k += 97) EXPECT_NEAR(range_m[k], range_mm[k], 1e-3);
  ASSERT_EQ(run_conicloc("map-export " + mm_map() + " --unit-scale 0.001 --obj " +
                             (dir_ / "mm.obj").string(),
                         dir_ / "export.log"),
            0)
      << slurp(dir_ / "export.log");
}

}  // namespace
