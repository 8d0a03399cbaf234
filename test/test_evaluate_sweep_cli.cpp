// `conicloc evaluate --sweep FILE --out DIR` end to end on a tiny sweep: the report files, the
// runs.csv columns, accurate tracking on a clean recording, and usage errors.
#include <gtest/gtest.h>

#include <algorithm>
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
  // The robustness columns right after `error` (their places since issue 14), then the rest.
  const std::vector<std::string> added{"error",        "building_group", "odometry", "capture_s",
                                       "false_alarms", "time_to_10cm_s", "lost"};
  const auto error_column = std::find(columns.begin(), columns.end(), "error");
  ASSERT_LE(added.size(), static_cast<std::size_t>(columns.end() - error_column)) << header;
  EXPECT_TRUE(std::equal(added.begin(), added.end(), error_column)) << header;
  const auto at = [&](const std::vector<std::string>& row, const std::string& name) {
    const auto column = std::find(columns.begin(), columns.end(), name);
    EXPECT_NE(column, columns.end()) << name;
    return row.at(static_cast<std::size_t>(column - columns.begin()));
  };
  ASSERT_TRUE(std::getline(csv, line));
  const auto row = split(line);
  ASSERT_EQ(row.size(), columns.size()) << line;
  EXPECT_EQ(row[0], "conic-beam");
  EXPECT_EQ(row[1], "default");  // what `conicloc localize` runs without options
  EXPECT_EQ(row[2], "default");
  EXPECT_EQ(row[10], "corridor-s1");
  EXPECT_EQ(at(row, "building_group"), "corridor-s1");
  EXPECT_EQ(at(row, "odometry"), "0");
  EXPECT_GT(std::stod(at(row, "capture_s")), 2.0);
  // The building's size and the time per scan by phase.
  EXPECT_EQ(at(row, "storeys"), "1");
  EXPECT_GT(std::stoi(at(row, "planes")), 20);
  EXPECT_GT(std::stod(at(row, "floor_area_m2")), 50.0);
  EXPECT_LT(std::stoul(at(row, "search_scans")), std::stoul(at(row, "scans")));
  EXPECT_GT(std::stod(at(row, "tracking_time_mean_ms")), 0.0);
  // Tracked from the true start, never 50 cm off: the place held from the first scan.
  EXPECT_EQ(at(row, "time_to_50cm_s"), "0.00");
  // The scenario's 2 cm map error: the map's pose of each scan written and scored beside the truth
  // (sim/map_fit.hpp); the two errors are those of one estimate against two references, and the
  // map's own is what sets them apart.
  EXPECT_TRUE(fs::exists(out / "runs/corridor-s1-robot-no-odom-s1.map-fit.tum"));
  const double to_truth = std::stod(at(row, "ate_xy_rmse_m"));
  const double map_share = std::stod(at(row, "map_fit_xy_rmse_m"));
  const double own_share = std::stod(at(row, "ate_xy_rmse_to_map_fit_m"));
  EXPECT_GT(map_share, 0.0);
  EXPECT_LT(map_share, 0.05);
  EXPECT_LE(to_truth, map_share + own_share + 1e-5);  // the triangle inequality, per scan
  const double map_heading = std::stod(at(row, "map_fit_heading_rmse_deg"));
  EXPECT_GT(map_heading, 0.0);
  // |Δyaw| is a distance on the circle: the same inequality, the columns written to 1e-4°.
  EXPECT_LE(std::stod(at(row, "heading_rmse_deg")),
            map_heading + std::stod(at(row, "heading_rmse_to_map_fit_deg")) + 2e-4);
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

namespace {

// runs.csv without the measured times (time_per_scan_ms, realtime_factor, time_p95_ms): what a
// merge of shards must reproduce exactly.
std::string without_times(const std::string& csv) {
  std::stringstream in(csv);
  std::string line, kept;
  std::vector<bool> skip;
  while (std::getline(in, line)) {
    const auto fields = split(line);
    if (skip.empty()) {
      for (const auto& name : fields)
        skip.push_back(name == "time_per_scan_ms" || name == "realtime_factor" ||
                       name == "time_p95_ms" || name == "start_time_ms" ||
                       name.rfind("search_time_", 0) == 0 || name == "tracking_time_mean_ms");
    }
    for (std::size_t i = 0; i < fields.size(); ++i) {
      if (i >= skip.size() || !skip[i]) kept += fields[i] + ",";
    }
    kept += "\n";
  }
  return kept;
}

std::size_t rows_of(const std::string& csv) {
  return static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n')) - 1;
}

}  // namespace

TEST_F(EvaluateSweepCli, ShardsResumeAndMergeIntoTheWholeSweep) {
  if (!fs::exists(CONICLOC_EXAMPLE_MAP)) GTEST_SKIP() << "no example building";
  // 2 seeds x 2 models: 4 runs; 3 shards hold 2, 1 and 1 of them.
  const std::string sweep = (dir_ / "tiny.sweep").string();
  std::ofstream(sweep) << "models = conic-beam, point-to-plane\nparticles = 60\nbeams = 150\n"
                          "seeds = 4, 5\nscenarios = clean\nduration_s = 2\nthreads = 1\n";
  const fs::path whole = dir_ / "whole";
  ASSERT_EQ(run_evaluate("--sweep " + sweep + " --out " + whole.string(), dir_ / "whole.txt"), 0)
      << slurp(dir_ / "whole.txt");
  std::vector<std::string> shards;
  for (int i = 1; i <= 3; ++i) {
    shards.push_back((dir_ / ("shard-" + std::to_string(i))).string());
    const fs::path log = dir_ / ("shard-" + std::to_string(i) + ".txt");
    ASSERT_EQ(run_evaluate("--sweep " + sweep + " --shard " + std::to_string(i) + "/3 --out " +
                               shards.back(),
                           log),
              0)
        << slurp(log);
  }
  EXPECT_EQ(rows_of(slurp(shards[0] + "/runs.csv")), 2u);
  EXPECT_EQ(rows_of(slurp(shards[1] + "/runs.csv")), 1u);
  EXPECT_FALSE(fs::exists(shards[0] + "/summary.md"));  // the merge writes the report

  // A shard stopped while writing its last run's line resumes and makes that run only.
  const std::string first = slurp(shards[0] + "/runs.csv");
  std::ofstream(shards[0] + "/runs.csv") << first.substr(0, first.size() - 30);
  ASSERT_EQ(
      run_evaluate("--sweep " + sweep + " --shard 1/3 --out " + shards[0], dir_ / "resume.txt"), 0)
      << slurp(dir_ / "resume.txt");
  EXPECT_NE(slurp(dir_ / "resume.txt").find("1 held already, 1 to make"), std::string::npos)
      << slurp(dir_ / "resume.txt");
  EXPECT_EQ(without_times(slurp(shards[0] + "/runs.csv")), without_times(first));

  // Merged in any order of the folders: the whole sweep's rows and accuracy, and its report.
  const fs::path merged = dir_ / "merged";
  ASSERT_EQ(run_evaluate("--merge " + shards[2] + " " + shards[0] + " " + shards[1] + " --out " +
                             merged.string(),
                         dir_ / "merge.txt"),
            0)
      << slurp(dir_ / "merge.txt");
  EXPECT_EQ(without_times(slurp(merged / "runs.csv")), without_times(slurp(whole / "runs.csv")));
  for (const char* file : {"summary.md", "robustness.md", "scale.md", "cost_against_size.svg",
                           "pareto.svg", "trajectory_clean.svg", "error_over_time_clean.svg"}) {
    EXPECT_TRUE(fs::exists(merged / file)) << file;
  }
  EXPECT_EQ(slurp(merged / "error_over_time_clean.svg"),
            slurp(whole / "error_over_time_clean.svg"));
  EXPECT_EQ(slurp(merged / "trajectory_clean.svg"), slurp(whole / "trajectory_clean.svg"));
}

TEST_F(EvaluateSweepCli, MergeNamesMissingAndDuplicatedRuns) {
  if (!fs::exists(CONICLOC_EXAMPLE_MAP)) GTEST_SKIP() << "no example building";
  const std::string sweep = (dir_ / "tiny.sweep").string();
  std::ofstream(sweep) << "models = conic-beam\nparticles = 60\nbeams = 150\nseeds = 4, 5\n"
                          "scenarios = clean\nduration_s = 2\nthreads = 1\n";
  const std::string one = (dir_ / "one").string();
  ASSERT_EQ(run_evaluate("--sweep " + sweep + " --shard 1/2 --out " + one, dir_ / "one.txt"), 0)
      << slurp(dir_ / "one.txt");

  EXPECT_EQ(run_evaluate("--merge " + one + " --out " + (dir_ / "m1").string(), dir_ / "m1.txt"),
            2);
  const std::string missing = slurp(dir_ / "m1.txt");
  EXPECT_NE(missing.find("example_building/clean/s5/conic-beam/p60/b150"), std::string::npos)
      << missing;
  EXPECT_NE(missing.find("missing"), std::string::npos) << missing;
  EXPECT_NE(missing.find(one), std::string::npos) << missing;

  EXPECT_EQ(run_evaluate("--merge " + one + " " + one + " --out " + (dir_ / "m2").string(),
                         dir_ / "m2.txt"),
            2);
  const std::string twice = slurp(dir_ / "m2.txt");
  EXPECT_NE(twice.find("example_building/clean/s4/conic-beam/p60/b150 is there twice"),
            std::string::npos)
      << twice;

  // A shard folder is not reused for another shard.
  EXPECT_EQ(run_evaluate("--sweep " + sweep + " --shard 2/2 --out " + one, dir_ / "other.txt"), 2);
  EXPECT_NE(slurp(dir_ / "other.txt").find("another sweep or shard"), std::string::npos)
      << slurp(dir_ / "other.txt");
}

TEST_F(EvaluateSweepCli, ShardMustBeIOfN) {
  for (const char* bad : {"0/4", "5/4", "2", "a/b"}) {
    EXPECT_NE(run_evaluate(
                  std::string("--sweep quick --shard ") + bad + " --out " + (dir_ / "o").string(),
                  dir_ / "bad.txt"),
              0)
        << bad;
    EXPECT_NE(slurp(dir_ / "bad.txt").find("1 <= I <= N"), std::string::npos)
        << slurp(dir_ / "bad.txt");
  }
  EXPECT_FALSE(fs::exists(dir_ / "o"));
}

TEST_F(EvaluateSweepCli, FinishedShardResumesToNothingWhateverTheMapPathLooksLike) {
  if (!fs::exists(CONICLOC_EXAMPLE_MAP)) GTEST_SKIP() << "no example building";
  const std::string sweep = (dir_ / "tiny.sweep").string();
  std::ofstream(sweep) << "models = conic-beam\nparticles = 60\nbeams = 150\nseeds = 4, 5\n"
                          "scenarios = clean\nduration_s = 2\nthreads = 1\n";
  const std::string shard = (dir_ / "shard").string();
  const std::string relative = fs::relative(CONICLOC_EXAMPLE_MAP, fs::current_path()).string();
  ASSERT_EQ(run_evaluate("--map " + relative + " --sweep " + sweep + " --shard 2/2 --out " + shard,
                         dir_ / "first.txt"),
            0)
      << slurp(dir_ / "first.txt");
  const std::string runs = slurp(shard + "/runs.csv");
  ASSERT_EQ(run_evaluate("--map " + std::string(CONICLOC_EXAMPLE_MAP) + " --sweep " + sweep +
                             " --shard 2/2 --out " + shard,
                         dir_ / "again.txt"),
            0)
      << slurp(dir_ / "again.txt");
  EXPECT_NE(slurp(dir_ / "again.txt").find("1 held already, 0 to make"), std::string::npos)
      << slurp(dir_ / "again.txt");
  EXPECT_EQ(slurp(shard + "/runs.csv"), runs);  // the same bytes: nothing made again
}
