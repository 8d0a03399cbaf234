#pragma once
// An evaluation sweep run into a folder (`conicloc evaluate --sweep … --out DIR`): recordings
// simulated in each building, localized with every setting of the sweep, scored; DIR gets
// runs.csv, summary.md, robustness.md, the plots (*.svg), the generated buildings' IndoorGML in
// DIR/buildings/, the recordings and estimates in DIR/runs/, and sweep.txt and shard.txt
// (sweep_folder.hpp). What happens on the way is told through SweepProgress; nothing is printed.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "eval/sweep_report.hpp"
#include "eval/sweep_scenario.hpp"
#include "eval/sweep_shard.hpp"
#include "eval/sweep_spec.hpp"
#include "eval/trajectory_metrics.hpp"
#include "io/indoorgml.hpp"

namespace conicloc::run {

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

/// The sweep's size, told once before the first run.
struct SweepOutline {
  std::size_t runs = 0;        ///< in the whole sweep
  std::size_t recordings = 0;  ///< (building, seed, scenario) triples
  std::size_t settings = 0;    ///< localizer settings run on each recording
  std::size_t held = 0;        ///< a shard's runs its runs.csv holds already
  std::size_t to_make = 0;     ///< runs made now
};

/// One run made (or failed), told as soon as runs.csv holds it.
struct SweepRunDone {
  std::size_t done = 0;   ///< runs in runs.csv now, this one included
  std::size_t share = 0;  ///< of this sweep or shard
  std::string building;   ///< eval::building_name() of the run's building
  const eval::Scenario* scenario = nullptr;
  std::uint64_t seed = 0;
  eval::LocalizerSetting setting;
  const eval::RunRecord* record = nullptr;  ///< valid during the call
};

/// How the caller follows a sweep; every callback may be empty.
struct SweepProgress {
  /// The sweep file's warnings, a building file's load warnings, a shard's cut runs.csv.
  std::function<void(const std::string& message)> warning;
  /// A building that cannot be generated or read, a recording that cannot be simulated: its runs
  /// are recorded as failed and the sweep goes on.
  std::function<void(const std::string& message)> error;
  std::function<void(const SweepOutline&)> started;
  std::function<void(const SweepRunDone&)> run_done;
};

struct SweepResult {
  std::vector<eval::RunRecord> runs;  ///< as in runs.csv: a shard's held runs, then those made
  int failed = 0;                     ///< of the runs made now
};

/// Runs the sweep, building by building and seed by seed; a run that throws (or whose building
/// cannot be generated or read) is recorded as failed and the sweep goes on. A whole sweep ends
/// with the report; a shard only with its runs.csv. Throws eval::ShardError when a shard's DIR
/// holds another sweep or shard; io::InputError before any work for a missing building file or
/// an unknown generated kind; std::invalid_argument for an unknown scenario.
SweepResult run_sweep(const SweepOptions& options, const SweepProgress& progress = {});

}  // namespace conicloc::run
