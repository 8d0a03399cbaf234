#pragma once
// `conicloc evaluate --map FILE --sweep quick|full|robustness|FILE --out DIR`: simulate
// recordings, localize them with every configuration of the sweep, score them, and write
// DIR/runs.csv, DIR/summary.md, DIR/robustness.md, DIR/*.svg and the generated buildings'
// IndoorGML in DIR/buildings/.

#include <optional>
#include <string>

#include "eval/sweep_shard.hpp"
#include "eval/sweep_spec.hpp"
#include "eval/trajectory_metrics.hpp"
#include "io/indoorgml.hpp"

namespace conicloc::tools {

struct SweepOptions {
  std::string map_path;            ///< an IndoorGML file or `generated:KIND[:SEED]`
  io::MapLoadOptions map_options;  ///< how the --map file is read (not the sweep file's `maps`)
  std::string out_dir;
  std::string command;  ///< the command line, quoted in the summary
  eval::SweepSpec spec;
  eval::MetricsConfig metrics;
  /// Only this shard's runs, resuming from its runs.csv; no report (a merge of the shards writes
  /// it). Empty: the whole sweep, afresh.
  std::optional<eval::Shard> shard;
};

/// Runs the sweep, building by building and seed by seed; a run that throws (or whose building
/// cannot be generated or read) is recorded as failed and the sweep goes on. Returns the number
/// of failed runs (of this shard's runs made now). DIR also gets sweep.txt and shard.txt
/// (sweep_folder.hpp). Throws eval::ShardError when a shard's DIR holds another sweep or shard.
/// Throws io::InputError before any work for a missing building file or an unknown generated kind.
int run_sweep(const SweepOptions& options);

}  // namespace conicloc::tools
