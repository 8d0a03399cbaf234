#pragma once
// Splitting a sweep's runs into N shards that run on different machines, resuming a stopped
// shard, and merging the shards' runs back into the unsharded sweep's order.
//
// Shard I of N (1-based: 1/4 … 4/4) holds the runs whose index in plan_runs() is I−1 modulo N:
// the same split on every machine, and every shard gets a share of each building and scenario.

#include <stdexcept>
#include <string>
#include <vector>

#include "eval/sweep_plan.hpp"
#include "eval/sweep_report.hpp"

namespace conicloc::eval {

/// A shard that cannot be run or merged: the message names the run and the folders.
class ShardError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Shard {
  int index = 1;  ///< 1 … count
  int count = 1;

  /// Whether the run with this index in plan_runs() belongs to the shard.
  bool holds(std::size_t run_index) const;
  std::string text() const;  ///< `I/N`
};

/// Reads `I/N` with 1 ≤ I ≤ N (whole numbers, N ≤ 1,000,000); throws std::invalid_argument
/// saying what was expected.
Shard parse_shard(const std::string& text);

/// Indices into `plan` of the runs the shard still has to make: its share, less the runs `held`
/// (its runs.csv) already holds. Throws ShardError naming the run when `held` has a run that is
/// not in the shard's share, or has one twice.
std::vector<std::size_t> pending_runs(const std::vector<RunKey>& plan, const Shard& shard,
                                      const std::vector<RunRecord>& held);

/// The runs found in one shard's folder.
struct ShardRuns {
  std::string dir;
  std::vector<RunRecord> runs;
};

/// Every run of `plan` exactly once, in the plan's order. Throws ShardError naming the run and
/// the folders for a run that no shard holds, one held twice (by one or two shards), and one that
/// is not in the plan.
std::vector<RunRecord> merge_shards(const std::vector<RunKey>& plan,
                                    const std::vector<ShardRuns>& shards);

}  // namespace conicloc::eval
