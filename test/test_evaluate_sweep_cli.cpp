// `conicloc evaluate --sweep FILE --out DIR` end to end on a tiny sweep: the report files, the
// runs.csv columns, accurate tracking on a clean recording, and usage errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "test/cli_run.hpp"
#include "test/temp_path.hpp"

namespace {

namespace fs = std::filesystem;
using conicloc::test::slurp;

int run_evaluate(const std::string& arguments, const fs::path& log) {
  return conicloc::test::run_conicloc("evaluate " + arguments, log);
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream stream(line);
  std::string field;
  while (std::getline(stream, field, ',')) fields.push_back(field);
  return fields;
}

class EvaluateSweepCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = conicloc::test::unique_temp_path("evaluate_sweep");
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

}  // namespace

TEST_F(EvaluateSweepCli, TinySweepWritesTheReport) {
  if (!fs::exists(CONICLOC_EXAMPLE_MAP)) GTEST_SKIP() << "no example building";
  std::ofstream(dir_ / "tiny.sweep") << "models = conic-beam, point-to-plane\n"
                                        "particles = 60\nbeams = 150\nseeds = 4\n"
                                        "scenarios = clean\nduration_s = 2\nthreads = 1\n";
  const fs::path out = dir_ / "report";
  ASSERT_EQ(run_evaluate("--sweep " + (dir_ / "tiny.sweep").string() + " --out " + out.string(),
                         dir_ / "log.txt"),
            0)
      << slurp(dir_ / "log.txt");
  for (const char* file : {"runs.csv", "summary.md", "pareto.svg", "error_over_time_clean.svg",
                           "trajectory_clean.svg", "runs/example_building-clean-s4.truth.tum"}) {
    EXPECT_TRUE(fs::exists(out / file)) << file;
  }
  EXPECT_FALSE(fs::exists(out / "runs/example_building-clean-s4.pcap"));  // not kept by default

  std::stringstream csv(slurp(out / "runs.csv"));
  std::string header, line;
  std::getline(csv, header);
  const auto columns = split(header);
  const std::vector<std::string> documented{"model",
                                            "particles",
                                            "beams",
                                            "seed",
                                            "scenario",
                                            "ate_xy_rmse_m",
                                            "heading_rmse_deg",
                                            "time_per_scan_ms",
                                            "realtime_factor",
                                            "converged"};
  ASSERT_GE(columns.size(), documented.size());
  EXPECT_TRUE(std::equal(documented.begin(), documented.end(), columns.begin())) << header;
  std::vector<std::vector<std::string>> rows;
  while (std::getline(csv, line)) rows.push_back(split(line));
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0][0], "conic-beam");
  EXPECT_EQ(rows[1][0], "point-to-plane");
  for (const auto& row : rows) {
    ASSERT_GE(row.size(), documented.size());
    EXPECT_EQ(row[1], "60");
    EXPECT_EQ(row[2], "150");
    EXPECT_EQ(row[3], "4");
    EXPECT_EQ(row[4], "clean");
    // A clean recording, tracked from the first true pose: centimetres, not metres.
    EXPECT_LT(std::stod(row[5]), 0.10) << line;
    EXPECT_GT(std::stod(row[7]), 0.0);
    EXPECT_EQ(row[9], "1");
  }
  const std::string summary = slurp(out / "summary.md");
  EXPECT_NE(summary.find("--sweep " + (dir_ / "tiny.sweep").string()), std::string::npos);
  EXPECT_NE(summary.find("| conic-beam | 60 | 150 |"), std::string::npos) << summary;
  // The plan shows the truth and each model's estimate as paths.
  const std::string plan = slurp(out / "trajectory_clean.svg");
  EXPECT_NE(plan.find("<polyline"), std::string::npos);
  EXPECT_NE(plan.find("point-to-plane (60 p)"), std::string::npos);
}

TEST_F(EvaluateSweepCli, UsageErrorsAreReported) {
  EXPECT_NE(run_evaluate("", dir_ / "none.txt"), 0);
  EXPECT_NE(slurp(dir_ / "none.txt").find("--out DIR"), std::string::npos)
      << slurp(dir_ / "none.txt");
  std::ofstream(dir_ / "bad.sweep") << "models = conic-beam\nparticles = many\n";
  EXPECT_NE(
      run_evaluate("--sweep " + (dir_ / "bad.sweep").string() + " --out " + (dir_ / "o").string(),
                   dir_ / "bad.txt"),
      0);
  const std::string bad = slurp(dir_ / "bad.txt");
  EXPECT_NE(bad.find("bad.sweep"), std::string::npos) << bad;
  EXPECT_NE(bad.find("line 2"), std::string::npos) << bad;
}

TEST_F(EvaluateSweepCli, ReducedRobustnessSweepOnAGeneratedBuilding) {
  // The robustness sweep cut down to one generated building, one scenario, one seed, 3 s.
  std::ofstream(dir_ / "reduced.sweep") << "base = robustness\nmaps =\nseeds = 1\n"
                                           "models = conic-beam\nscenarios = robot-no-odom\n"
                                           "duration_s = 3\nthreads = 1\n";
  const fs::path out = dir_ / "report";
  ASSERT_EQ(run_evaluate("--map generated:corridor:1 --sweep " + (dir_ / "reduced.sweep").string() +
                             " --out " + out.string(),
                         dir_ / "log.txt"),
            0)
      << slurp(dir_ / "log.txt");
  EXPECT_TRUE(fs::exists(out / "buildings/corridor-1.gml"));  // read back like any map
  EXPECT_TRUE(fs::exists(out / "runs/corridor-s1-robot-no-odom-s1.truth.tum"));

  std::stringstream csv(slurp(out / "runs.csv"));
  std::string header, line;
  std::getline(csv, header);
  const auto columns = split(header);
  const std::vector<std::string> added{"building_group", "odometry",       "capture_s",
                                       "false_alarms",   "time_to_10cm_s", "lost"};
  ASSERT_GE(columns.size(), added.size());
  EXPECT_TRUE(std::equal(added.begin(), added.end(), columns.end() - 6)) << header;
  ASSERT_TRUE(std::getline(csv, line));
  const auto row = split(line);
  ASSERT_EQ(row.size(), columns.size()) << line;
  EXPECT_EQ(row[0], "conic-beam");
  EXPECT_EQ(row[1], "default");  // what `conicloc localize` runs without options
  EXPECT_EQ(row[2], "default");
  EXPECT_EQ(row[10], "corridor-s1");
  EXPECT_EQ(row[columns.size() - 6], "corridor-s1");
  EXPECT_EQ(row[columns.size() - 5], "0");  // no odometry
  EXPECT_GT(std::stod(row[columns.size() - 4]), 2.0);
  EXPECT_FALSE(std::getline(csv, line));

  const std::string robustness = slurp(out / "robustness.md");
  EXPECT_NE(robustness.find("| conic-beam | corridor-s1 | robot-no-odom | 1 |"), std::string::npos)
      << robustness;
  EXPECT_NE(slurp(out / "summary.md").find("## Robustness: targets"), std::string::npos);

  // An unknown generated kind is refused before any work.
  EXPECT_NE(run_evaluate("--map generated:castle --sweep " + (dir_ / "reduced.sweep").string() +
                             " --out " + (dir_ / "o").string(),
                         dir_ / "castle.txt"),
            0);
  EXPECT_NE(slurp(dir_ / "castle.txt").find("castle"), std::string::npos)
      << slurp(dir_ / "castle.txt");
}
