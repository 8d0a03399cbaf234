#pragma once
// `conicloc evaluate --map FILE --sweep quick|full|robustness|FILE --out DIR`: simulate
// recordings, localize them with every configuration of the sweep, score them, and write
// DIR/runs.csv, DIR/summary.md, DIR/robustness.md, DIR/*.svg and the generated buildings'
// IndoorGML in DIR/buildings/.

#include <string>

#include "eval/sweep_spec.hpp"
#include "eval/trajectory_metrics.hpp"

namespace conicloc::tools {

struct SweepOptions {
  std::string map_path;  ///< an IndoorGML file or `generated:KIND[:SEED]`
  std::string out_dir;
  std::string command;  ///< the command line, quoted in the summary
  eval::SweepSpec spec;
  eval::MetricsConfig metrics;
};

/// Runs the sweep, building by building and seed by seed; a run that throws (or whose building
/// cannot be generated or read) is recorded as failed and the sweep goes on. Returns the number
/// of failed runs. Throws io::InputError before any work for a missing building file or an
/// unknown generated kind.
int run_sweep(const SweepOptions& options);

}  // namespace conicloc::tools
