#pragma once
// `conicloc evaluate --map FILE --sweep quick|full|FILE --out DIR`: simulate recordings, localize
// them with every configuration of the sweep, score them, and write DIR/runs.csv, DIR/summary.md
// and DIR/*.svg.

#include <string>

#include "eval/sweep_spec.hpp"
#include "eval/trajectory_metrics.hpp"

namespace conicloc::tools {

struct SweepOptions {
  std::string map_path;
  std::string out_dir;
  std::string command;  ///< the command line, quoted in the summary
  eval::SweepSpec spec;
  eval::MetricsConfig metrics;
};

/// Runs the sweep; a run that throws is recorded as failed and the sweep goes on. Returns the
/// number of failed runs.
int run_sweep(const SweepOptions& options);

}  // namespace conicloc::tools
