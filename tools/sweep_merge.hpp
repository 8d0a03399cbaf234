#pragma once
// `conicloc evaluate --merge DIR_1 … DIR_N --out DIR`: the shards of one sweep (each run with
// `--shard I/N`) into the report the whole sweep writes: runs.csv in the sweep's order, summary.md,
// robustness.md and the plots, with the runs' recordings and estimates copied into DIR/runs.

#include <string>
#include <vector>

namespace conicloc::tools {

struct MergeOptions {
  std::vector<std::string> shard_dirs;
  std::string out_dir;
  std::string command;  ///< the command line, quoted in the summary
};

/// Merges the shards; returns the number of failed runs among them. Throws eval::ShardError when
/// the folders are not shards of one sweep (their sweep.txt or shard.txt differ, or one has none),
/// or a run is missing, held twice or not in the sweep (the message names the run and folders);
/// io::InputError for an unreadable runs.csv or trajectory file.
int merge_sweep(const MergeOptions& options);

}  // namespace conicloc::tools
