#pragma once
// Cost against building size (issue 15): per model × scenario × building, the building's size
// (storeys, planes, navigable floor area) beside the time per scan while the filter searched and
// while it tracked, the worst searching scan, the start's cost and the time to converge. Read with
// `conicloc evaluate --sweep scale`, whose buildings grow in storeys and in floor plates.

#include <string>
#include <vector>

#include "eval/sweep_report.hpp"

namespace conicloc::eval {

/// One row of the table: the runs of one localizer setting and scenario in one building, over
/// seeds.
struct ScaleRow {
  std::string model;
  int particles = 0;  ///< as RunRecord (kDefaultSetting: the localizer's defaults)
  int beams = 0;
  std::string scenario;
  std::string building;
  int storeys = 0;
  std::size_t planes = 0;
  double floor_area_m2 = 0.0;
  int runs = 0;                        ///< completed runs (failed runs stay out)
  double tracking_time_mean_ms = 0.0;  ///< mean over the runs that tracked
  double search_time_mean_ms = 0.0;    ///< mean over the runs that searched; NaN when none did
  double search_time_max_ms = 0.0;     ///< the worst searching scan of any run
  double start_time_ms = 0.0;          ///< mean
  double realtime_factor = 0.0;        ///< mean
  int settled = 0;                     ///< runs at ≤ 10 cm within 10 s
  double settle_time_mean_s = 0.0;     ///< over the settled runs; NaN when none settled
};

/// The rows, ordered by model, particles, beams, scenario, then floor area and storeys (smallest
/// building first). Failed runs and runs without the size columns (a runs.csv from before them:
/// no planes) stay out.
std::vector<ScaleRow> scale_rows(const std::vector<RunRecord>& runs);

/// Markdown (`##` section) of scale_rows; says so when the runs hold no completed run.
std::string scale_markdown(const std::vector<RunRecord>& runs);

/// SVG chart: time per scan (searching and tracking, one series each per model × scenario)
/// against the navigable floor area, log-log.
std::string scale_svg(const std::vector<RunRecord>& runs);

}  // namespace conicloc::eval
