// The cost-against-size report of an evaluation sweep (issue 15): one row per model × scenario ×
// building over seeds, smallest building first, searching and tracking times kept apart.
#include <gtest/gtest.h>

#include <cmath>

#include "eval/scale_report.hpp"

namespace ce = conicloc::eval;

namespace {

ce::RunRecord run(const std::string& building, double floor_area_m2, std::size_t search_scans,
                  double search_mean_ms, double search_max_ms, double tracking_mean_ms) {
  ce::RunRecord r;
  r.model = "conic-beam";
  r.particles = ce::kDefaultSetting;
  r.beams = ce::kDefaultSetting;
  r.scenario = "global";
  r.building = building;
  r.storeys = 2;
  r.planes = 80;
  r.floor_area_m2 = floor_area_m2;
  r.scans = 100;
  r.search_scans = search_scans;
  r.search_time_mean_ms = search_mean_ms;
  r.search_time_max_ms = search_max_ms;
  r.tracking_time_mean_ms = tracking_mean_ms;
  r.realtime_factor = 2.0;
  return r;
}

}  // namespace

TEST(ScaleReport, OneRowPerBuildingOverSeedsSmallestFirst) {
  std::vector<ce::RunRecord> runs;
  runs.push_back(run("big", 1000.0, 10, 200.0, 400.0, 20.0));
  runs.back().time_to_10cm_s = 3.0;
  runs.push_back(run("big", 1000.0, 30, 100.0, 900.0, 10.0));
  runs.back().time_to_10cm_s = 12.0;                      // after the 10 s limit: not settled
  runs.push_back(run("small", 250.0, 0, 0.0, 0.0, 8.0));  // tracked from its first scan
  runs.back().time_to_10cm_s = 0.0;
  runs.push_back(run("small", 250.0, 5, 50.0, 60.0, 6.0));
  runs.back().failed = true;  // stays out
  runs.push_back(run("small", 250.0, 5, 50.0, 60.0, 6.0));
  runs.back().planes = 0;  // from a runs.csv without the size columns: stays out
  runs.push_back(run("small", 250.0, 0, 0.0, 0.0, 30.0));
  runs.back().particles = 1000;  // another setting: its own row
  const auto rows = ce::scale_rows(runs);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[2].particles, 1000);
  EXPECT_DOUBLE_EQ(rows[2].tracking_time_mean_ms, 30.0);
  EXPECT_EQ(rows[0].building, "small");
  EXPECT_EQ(rows[0].runs, 1);
  EXPECT_TRUE(std::isnan(rows[0].search_time_mean_ms));  // never searched
  EXPECT_DOUBLE_EQ(rows[0].tracking_time_mean_ms, 8.0);
  EXPECT_EQ(rows[0].settled, 1);
  EXPECT_EQ(rows[1].building, "big");
  EXPECT_EQ(rows[1].runs, 2);
  EXPECT_DOUBLE_EQ(rows[1].search_time_mean_ms, 150.0);
  EXPECT_DOUBLE_EQ(rows[1].search_time_max_ms, 900.0);
  EXPECT_DOUBLE_EQ(rows[1].tracking_time_mean_ms, 15.0);
  EXPECT_EQ(rows[1].settled, 1);
  EXPECT_DOUBLE_EQ(rows[1].settle_time_mean_s, 3.0);

  const std::string md = ce::scale_markdown(runs);
  EXPECT_NE(
      md.find("| conic-beam | default | default | global | small | 2 | 80 | 250 | 1 | 8.0 | — "
              "| — |"),
      std::string::npos)
      << md;
  EXPECT_NE(md.find("| conic-beam | default | default | global | big | 2 | 80 | 1000 | 2 | 15.0 | "
                    "150.0 | 900 |"),
            std::string::npos)
      << md;
  const std::string svg = ce::scale_svg(runs);
  EXPECT_NE(svg.find("conic-beam, global: searching"), std::string::npos);
}

TEST(ScaleReport, SaysSoWithoutACompletedRun) {
  auto only = run("b", 100.0, 0, 0.0, 0.0, 5.0);
  only.failed = true;
  EXPECT_NE(ce::scale_markdown({only}).find("No completed run"), std::string::npos);
}
