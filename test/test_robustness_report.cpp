// The robustness report of an evaluation sweep (issue 14): which runs count as lost, which lost
// alarms were false, and the tables per model × building × scenario with the targets' verdicts.
#include <gtest/gtest.h>

#include "eval/lost_alarms.hpp"
#include "eval/robustness_report.hpp"
#include "eval/runs_csv_reader.hpp"
#include "eval/sweep_report.hpp"
#include "localizer/conic/pose.hpp"

namespace ce = conicloc::eval;
using conicloc::io::StampedPose;
using conicloc::localizer::make_pose;

namespace {

ce::RunRecord tracking_run(const std::string& building, double rmse, double max_xy) {
  ce::RunRecord r;
  r.building = building;
  r.scenario = "robot-no-odom";
  r.model = "conic-beam";
  r.metrics.ate_xy_m.rmse = rmse;
  r.metrics.ate_xy_m.max = max_xy;
  r.metrics.heading_deg.rmse = 0.2;
  r.metrics.matched = 100;
  r.time_per_scan_ms = 10.0;
  r.capture_s = 1800.0;
  return r;
}

ce::RunRecord start_run(const std::string& scenario, std::optional<double> time_to_10cm_s) {
  ce::RunRecord r = tracking_run("b", 0.5, 4.0);
  r.scenario = scenario;
  r.time_to_10cm_s = time_to_10cm_s;
  return r;
}

}  // namespace

TEST(LostAlarms, FalseOnlyWhereTheEstimateWasWithinHalfAMetreOfTheTruth) {
  const std::vector<StampedPose> truth{{0.0, make_pose(0, 0, 1, 0)}, {1.0, make_pose(1, 0, 1, 0)}};
  const std::vector<StampedPose> alarms{
      {0.5, make_pose(0.9, 0, 1, 0)},     // 0.4 m off the truth (0.5, 0): a false alarm
      {0.5, make_pose(1.1, 0, 1, 0)},     // 0.6 m off: the filter was lost indeed
      {0.5, make_pose(0.5, 0.49, 5, 0)},  // height does not count: 0.49 m, false
      {7.0, make_pose(0, 0, 1, 0)}};      // no truth around it: cannot be judged
  EXPECT_EQ(ce::count_false_alarms(truth, alarms, 1.0), 2u);
  EXPECT_EQ(ce::count_false_alarms(truth, alarms, 1.0, 0.3), 0u);
  EXPECT_EQ(ce::count_false_alarms(truth, {}, 1.0), 0u);
}

TEST(RobustnessReport, LostRuns) {
  EXPECT_TRUE(ce::lost_run(tracking_run("b", 0.05, 0.6)));   // once more than 0.5 m off
  EXPECT_FALSE(ce::lost_run(tracking_run("b", 0.05, 0.5)));  // at the limit: not lost
  auto unmatched = tracking_run("b", 0.0, 0.0);
  unmatched.metrics.matched = 0;
  EXPECT_TRUE(ce::lost_run(unmatched));
  auto failed = tracking_run("b", 0.01, 0.02);
  failed.failed = true;
  EXPECT_TRUE(ce::lost_run(failed));
  // Global start and kidnap: at 10 cm within 10 s, whatever the error before.
  EXPECT_FALSE(ce::lost_run(start_run("global", 9.5)));
  EXPECT_TRUE(ce::lost_run(start_run("global-no-odom", 10.5)));
  EXPECT_TRUE(ce::lost_run(start_run("kidnap", std::nullopt)));
  EXPECT_FALSE(ce::lost_run(start_run("kidnap-no-odom", 0.0)));
}

// The robustness columns keep their places after `error` (scripts index them); the cost-against-
// size columns come after them, then the time to 50 cm, last.
TEST(RobustnessReport, RunsCsvKeepsTheRobustnessColumnsThenAppendsTheScaleColumns) {
  auto r = tracking_run("corridor-s2", 0.03, 0.6);
  r.particles = ce::kDefaultSetting;
  r.beams = ce::kDefaultSetting;
  r.building_group = "corridor-s*";
  r.odometry = false;
  r.false_alarms = 2;
  r.time_to_10cm_s = 4.5;
  r.storeys = 3;
  r.planes = 120;
  r.floor_area_m2 = 812.25;
  r.start_time_ms = 41.5;
  r.search_scans = 7;
  r.search_time_mean_ms = 88.125;
  r.search_time_max_ms = 140.5;
  r.tracking_time_mean_ms = 9.25;
  r.time_to_50cm_s = 3.25;
  r.map_fit_xy_rmse_m = 0.0412;
  r.ate_xy_rmse_to_map_fit_m = 0.0123;
  r.map_fit_heading_rmse_deg = 0.25;
  r.heading_rmse_to_map_fit_deg = 0.125;
  const std::string csv = ce::runs_csv({r});
  const std::string header = csv.substr(0, csv.find('\n'));
  const std::string tail =
      ",error,building_group,odometry,capture_s,false_alarms,time_to_10cm_s,lost,storeys,planes,"
      "floor_area_m2,start_time_ms,search_scans,search_time_mean_ms,search_time_max_ms,"
      "tracking_time_mean_ms,time_to_50cm_s,map_fit_xy_rmse_m,ate_xy_rmse_to_map_fit_m,"
      "map_fit_heading_rmse_deg,heading_rmse_to_map_fit_deg";
  EXPECT_EQ(header.substr(header.size() - tail.size()), tail) << header;
  const std::string row = csv.substr(csv.find('\n') + 1);
  EXPECT_EQ(row.rfind("conic-beam,default,default,0,robot-no-odom,", 0), 0u) << row;
  EXPECT_NE(
      row.find(",corridor-s*,0,1800.00,2,4.50,1,3,120,812.2,41.500,7,88.125,140.500,9.250,3.25,"
               "0.04120,0.01230,0.2500,0.1250\n"),
      std::string::npos)
      << row;
  // Read back as written.
  const auto back = ce::read_runs_csv(csv, "runs.csv").runs.at(0);
  EXPECT_EQ(back.storeys, 3);
  EXPECT_EQ(back.planes, 120u);
  EXPECT_EQ(back.search_scans, 7u);
  EXPECT_DOUBLE_EQ(back.search_time_max_ms, 140.5);
  EXPECT_DOUBLE_EQ(back.tracking_time_mean_ms, 9.25);
  EXPECT_DOUBLE_EQ(back.time_to_50cm_s.value_or(-1.0), 3.25);
}

TEST(RobustnessReport, TablesAggregateOverSeedsAndJudgeTheTargets) {
  std::vector<ce::RunRecord> runs;
  // A building generated per seed: two seeds, one row. Seed 2 once 0.6 m off: lost.
  runs.push_back(tracking_run("corridor-s1", 0.02, 0.3));
  runs.back().building_group = "corridor-s*";
  runs.back().false_alarms = 1;
  runs.back().recoveries = 1;
  runs.push_back(tracking_run("corridor-s2", 0.04, 0.6));
  runs.back().building_group = "corridor-s*";
  runs.back().seed = 2;
  // A file building, accurate: every tracking target met.
  runs.push_back(tracking_run("example", 0.03, 0.1));
  runs.back().model = "conic-segment";
  // Global starts: 1 of 2 at 10 cm within 10 s; both had found the place within 10 s (the
  // second, beyond 10 cm late in the run, is a tracking error, not a look-alike).
  runs.push_back(start_run("global", 4.0));
  runs.back().time_to_50cm_s = 3.0;
  runs.push_back(start_run("global", 12.0));
  runs.back().time_to_50cm_s = 9.0;
  const std::string md = ce::robustness_markdown(runs);

  EXPECT_NE(md.find("| conic-beam | corridor-s* | robot-no-odom | 2 | 1 | 0.0300 | 0.200 |  | 1 | "
                    "1 | 10.0 |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| conic-beam | b | global | 2 | 1 | 0.5000 | 0.200 | 4.0 | 0 | 0 | 10.0 |"),
            std::string::npos)
      << md;
  EXPECT_NE(
      md.find("| conic-beam | robot-no-odom | 2 | 1 | 0.0300 / 0.0400 | 0.200 / 0.200 | 1 | 1 "
              "| never lost ✗, xy ≤ 5 cm ✓, heading ≤ 0.5° ✓, no recoveries ✗ | FAIL |"),
      std::string::npos)
      << md;
  EXPECT_NE(md.find("| conic-segment | robot-no-odom | 1 | 0 | 0.0300 / 0.0300 | 0.200 / 0.200 | 0 "
                    "| 0 | never lost ✓, xy ≤ 5 cm ✓, heading ≤ 0.5° ✓, no recoveries ✓ | pass |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("at 10 cm within 10 s: 1/2 (50 %) ✗; at 50 cm (place found): 2/2 | FAIL |"),
            std::string::npos)
      << md;
  // Runs read from a runs.csv older than time_to_50cm_s: no count of places found, not 0/2.
  for (auto& run : runs) run.scored_at_50cm = run.scenario != "global";
  const std::string older = ce::robustness_markdown(runs);
  EXPECT_NE(older.find("at 10 cm within 10 s: 1/2 (50 %) ✗ | FAIL |"), std::string::npos) << older;
  for (auto& run : runs) run.scored_at_50cm = true;
  // The lost alarm over the tracking runs only: 1 false alarm in 2 × 30 min.
  EXPECT_NE(md.find("| conic-beam | 1.000 | 1 | 1.0 | 1/2 (50 %) |"), std::string::npos) << md;
  EXPECT_NE(md.find("| conic-segment | 0.500 | 0 | 0.0 | 0/1 (0 %) |"), std::string::npos) << md;

  // The summary carries the same tables.
  EXPECT_NE(ce::summary_markdown(runs, "c", {}).find(md), std::string::npos);
  EXPECT_EQ(ce::robustness_markdown({}), "");
}

TEST(RobustnessReport, UnderMapErrorTheMapsShareStandsBesideTheLocalizers) {
  auto a = tracking_run("b", 0.062, 0.09);
  a.scenario = "map-error-5cm";
  a.map_fit_xy_rmse_m = 0.060;
  a.ate_xy_rmse_to_map_fit_m = 0.011;
  a.metrics.heading_deg.rmse = 0.61;
  a.map_fit_heading_rmse_deg = 0.58;
  a.heading_rmse_to_map_fit_deg = 0.12;
  auto b = a;
  b.metrics.ate_xy_m.rmse = 0.030;
  b.map_fit_xy_rmse_m = 0.026;
  b.ate_xy_rmse_to_map_fit_m = 0.013;
  b.metrics.heading_deg.rmse = 0.21;
  b.map_fit_heading_rmse_deg = 0.18;
  b.heading_rmse_to_map_fit_deg = 0.1;
  auto c = b;  // another scenario: a row of its own
  c.scenario = "robot";
  const std::string md = ce::robustness_markdown({a, b, c, tracking_run("b", 0.02, 0.05)});
  EXPECT_NE(md.find("what the map allows"), std::string::npos) << md;
  // Mean / worst / runs over 5 cm, over the two map-error runs only.
  EXPECT_NE(
      md.find("| conic-beam | map-error-5cm | 2 | 0.0460 / 0.0620 / 1 | 0.0430 / 0.0600 / 1 | "
              "0.0120 / 0.0130 / 0 | 0.410 / 0.610 / 1 | 0.380 / 0.580 / 1 | "
              "0.110 / 0.120 / 0 |\n"),
      std::string::npos)
      << md;
  EXPECT_NE(md.find("| conic-beam | robot | 1 | 0.0300 / 0.0300 / 0 |"), std::string::npos) << md;
  // Without map-fit figures there is no such table.
  EXPECT_EQ(ce::robustness_markdown({tracking_run("b", 0.02, 0.05)}).find("what the map allows"),
            std::string::npos);
}
