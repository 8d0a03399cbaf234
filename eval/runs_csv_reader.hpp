#pragma once
// Reads back the runs.csv that runs_csv() writes, so a stopped shard can resume and shards can be
// merged: columns are found by their header names; runs_csv(read_runs_csv(runs_csv(r)).runs) is
// runs_csv(r). Per-pose errors are not in the file (TrajectoryMetrics::errors stays empty).

#include <string>
#include <vector>

#include "eval/sweep_report.hpp"

namespace conicloc::eval {

struct RunsCsv {
  std::vector<RunRecord> runs;
  /// The last line was cut short (no newline at its end, or too few fields): a run stopped while
  /// the file was written. It is left out, so that run is made again.
  bool dropped_partial_line = false;
};

/// Parses runs.csv text; `file` names it in errors. A run failed when its `error` is not empty.
/// Throws io::InputError naming the file and line for a missing key column (model, particles,
/// beams, seed, scenario, building) or a line before the last with the wrong number of fields or
/// a bad number.
RunsCsv read_runs_csv(const std::string& text, const std::string& file);

}  // namespace conicloc::eval
