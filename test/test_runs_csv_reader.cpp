// Reading runs.csv back: every column round-trips, a line cut short at the end is dropped (its
// run is made again), and a damaged line before it is an error naming the file and line.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "eval/runs_csv_reader.hpp"
#include "eval/sweep_report.hpp"
#include "io/input_error.hpp"

namespace ce = conicloc::eval;

namespace {

std::vector<ce::RunRecord> sample_runs() {
  ce::RunRecord tracked;
  tracked.building = "example_building";
  tracked.building_group = "example_building";
  tracked.scenario = "robot";
  tracked.seed = 1;
  tracked.model = "conic-beam";
  tracked.particles = 300;
  tracked.beams = 1000;
  tracked.threads = 2;
  tracked.cores = 2;
  auto& m = tracked.metrics;
  m.ate_xy_m = {.rmse = 0.02534, .mean = 0.021, .median = 0.0199, .max = 0.0711, .count = 99};
  m.ate_z_m.rmse = 0.00812;
  m.heading_deg.rmse = 0.1152;
  m.heading_deg.max = 0.4021;
  m.rpe_trans_per_m.rmse = 0.012345;
  m.rpe_rot_deg_per_m.rmse = 0.04321;
  m.convergence_time_s = 0.0;
  m.matched = 99;
  m.missing = 1;
  tracked.converged = true;
  tracked.time_per_scan_ms = 3.912;
  tracked.time_p95_ms = 4.31;
  tracked.realtime_factor = 25.4;
  tracked.mean_particles = 201.5;
  tracked.scans = 100;
  tracked.recoveries = 2;
  tracked.estimate_file = "runs/example_building-robot-s1-conic-beam-p300-b1000.tum";
  tracked.capture_s = 9.9;
  tracked.false_alarms = 1;
  tracked.time_to_10cm_s = 0.5;
  tracked.time_to_50cm_s = 0.25;
  tracked.map_fit_xy_rmse_m = 0.0487;
  tracked.ate_xy_rmse_to_map_fit_m = 0.0114;
  tracked.map_fit_heading_rmse_deg = 0.2125;
  tracked.heading_rmse_to_map_fit_deg = 0.0625;

  ce::RunRecord global = tracked;
  global.building = "corridor-s2";
  global.building_group = "corridor-s*";
  global.scenario = "global-no-odom";
  global.seed = 2;
  global.model = "conic-segment";
  global.particles = ce::kDefaultSetting;
  global.beams = 0;
  global.odometry = false;
  global.converged = false;
  global.metrics.convergence_time_s.reset();
  global.time_to_10cm_s.reset();
  global.time_to_50cm_s = 7.5;  // the place found, never within 10 cm
  global.map_fit_xy_rmse_m.reset();  // no map error
  global.ate_xy_rmse_to_map_fit_m.reset();
  global.map_fit_heading_rmse_deg.reset();
  global.heading_rmse_to_map_fit_deg.reset();

  ce::RunRecord failed;
  failed.building = "FJK";
  failed.scenario = "kidnap";
  failed.seed = 3;
  failed.model = "point-to-plane";
  failed.particles = 1000;
  failed.beams = ce::kDefaultSetting;
  failed.failed = true;
  failed.error = "simulation: no route; none at all";
  return {tracked, global, failed};
}

}  // namespace

TEST(RunsCsvReader, EveryColumnRoundTrips) {
  const std::string csv = ce::runs_csv(sample_runs());
  const auto read = ce::read_runs_csv(csv, "runs.csv");
  EXPECT_FALSE(read.dropped_partial_line);
  ASSERT_EQ(read.runs.size(), 3u);
  EXPECT_EQ(ce::runs_csv(read.runs), csv);
  EXPECT_EQ(read.runs[1].particles, ce::kDefaultSetting);
  EXPECT_FALSE(read.runs[1].odometry);
  EXPECT_FALSE(read.runs[1].time_to_10cm_s.has_value());
  EXPECT_TRUE(read.runs[1].scored_at_50cm);
  EXPECT_EQ(read.runs[0].map_fit_xy_rmse_m, 0.0487);
  EXPECT_EQ(read.runs[0].ate_xy_rmse_to_map_fit_m, 0.0114);
  EXPECT_EQ(read.runs[0].map_fit_heading_rmse_deg, 0.2125);
  EXPECT_EQ(read.runs[0].heading_rmse_to_map_fit_deg, 0.0625);
  EXPECT_FALSE(read.runs[1].map_fit_xy_rmse_m.has_value());
  // A runs.csv written before the time_to_50cm_s column (and the map-fit columns after it): read,
  // marked unscored.
  const auto without_columns_from = [&](const std::string& column) {
    const std::string header = csv.substr(0, csv.find('\n'));
    const auto dropped =
        std::count(header.begin() + static_cast<long>(header.find(column)), header.end(), ',');
    std::string older = header.substr(0, header.find(column)) + "\n";
    std::stringstream in(csv.substr(csv.find('\n') + 1));
    for (std::string line; std::getline(in, line);) {
      for (long k = 0; k < dropped; ++k) line.erase(line.rfind(','));
      older += line + "\n";
    }
    return older;
  };
  const auto map_fit_read = ce::read_runs_csv(without_columns_from(",map_fit_xy_rmse_m"), "o.csv");
  ASSERT_EQ(map_fit_read.runs.size(), 3u);
  EXPECT_FALSE(map_fit_read.runs[0].map_fit_xy_rmse_m.has_value());
  EXPECT_FALSE(map_fit_read.runs[0].ate_xy_rmse_to_map_fit_m.has_value());
  EXPECT_FALSE(map_fit_read.runs[0].map_fit_heading_rmse_deg.has_value());
  EXPECT_FALSE(map_fit_read.runs[0].heading_rmse_to_map_fit_deg.has_value());
  EXPECT_EQ(map_fit_read.runs[0].time_to_50cm_s, 0.25);
  const auto old_read = ce::read_runs_csv(without_columns_from(",time_to_50cm_s"), "old.csv");
  ASSERT_EQ(old_read.runs.size(), 3u);
  EXPECT_FALSE(old_read.runs[0].scored_at_50cm);
  EXPECT_FALSE(old_read.runs[1].time_to_50cm_s.has_value());
  EXPECT_EQ(old_read.runs[1].metrics.ate_xy_m.rmse, read.runs[1].metrics.ate_xy_m.rmse);
  EXPECT_FALSE(read.runs[0].failed);
  EXPECT_TRUE(read.runs[2].failed);
  EXPECT_EQ(read.runs[2].error, "simulation: no route; none at all");
}

TEST(RunsCsvReader, ALineCutShortAtTheEndIsDropped) {
  const std::string csv = ce::runs_csv(sample_runs());
  const auto last_line = csv.rfind('\n', csv.size() - 2) + 1;
  for (std::size_t end = last_line + 1; end < csv.size(); end += 7) {
    const auto read = ce::read_runs_csv(csv.substr(0, end), "runs.csv");
    EXPECT_TRUE(read.dropped_partial_line) << end;
    EXPECT_EQ(read.runs.size(), 2u) << end;
  }
  // Cut right after a whole line: nothing is lost.
  const auto whole = ce::read_runs_csv(csv.substr(0, last_line), "runs.csv");
  EXPECT_FALSE(whole.dropped_partial_line);
  EXPECT_EQ(whole.runs.size(), 2u);
  // Only part of the header: no runs yet.
  const auto header = ce::read_runs_csv(csv.substr(0, 20), "runs.csv");
  EXPECT_TRUE(header.runs.empty());
  EXPECT_TRUE(ce::read_runs_csv("", "runs.csv").runs.empty());
}

TEST(RunsCsvReader, DamageBeforeTheLastLineNamesFileAndLine) {
  std::string csv = ce::runs_csv(sample_runs());
  const auto second = csv.find('\n') + 1;
  std::string short_line = csv;
  short_line.erase(second, csv.find(',', second) + 1 - second);  // one field fewer on line 2
  try {
    ce::read_runs_csv(short_line, "out/runs.csv");
    ADD_FAILURE() << "no error";
  } catch (const conicloc::io::InputError& e) {
    EXPECT_EQ(e.file(), "out/runs.csv");
    EXPECT_EQ(e.place(), "line 2");
  }
  std::string bad_number = csv;
  bad_number.replace(bad_number.find("0.02534"), 7, "0.0x534");
  try {
    ce::read_runs_csv(bad_number, "out/runs.csv");
    ADD_FAILURE() << "no error";
  } catch (const conicloc::io::InputError& e) {
    EXPECT_EQ(e.place(), "line 2");
    EXPECT_NE(std::string(e.what()).find("ate_xy_rmse_m"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ce::read_runs_csv("model,particles,seed\nconic-beam,1,1\n", "x.csv"),
               conicloc::io::InputError);  // no beams, scenario or building column
}
