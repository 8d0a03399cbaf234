#include "eval/sweep_shard.hpp"

#include <fmt/format.h>

#include <map>
#include <optional>
#include <set>

namespace conicloc::eval {
namespace {

std::optional<int> whole_number(const std::string& text) {
  if (text.empty() || text.size() > 7) return std::nullopt;
  int value = 0;
  for (const char c : text) {
    if (c < '0' || c > '9') return std::nullopt;
    value = value * 10 + (c - '0');
  }
  return value;
}

}  // namespace

bool Shard::holds(std::size_t run_index) const {
  return run_index % static_cast<std::size_t>(count) == static_cast<std::size_t>(index - 1);
}

std::string Shard::text() const {
  return fmt::format("{}/{}", index, count);
}

Shard parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  const auto index = whole_number(text.substr(0, slash));
  const auto count =
      slash == std::string::npos ? std::nullopt : whole_number(text.substr(slash + 1));
  if (!index || !count || *count < 1 || *count > 1000000 || *index < 1 || *index > *count) {
    throw std::invalid_argument(
        "expected I/N with 1 <= I <= N (shards count from 1: 1/4 ... 4/4), "
        "got '" +
        text + "'");
  }
  return {*index, *count};
}

std::vector<std::size_t> pending_runs(const std::vector<RunKey>& plan, const Shard& shard,
                                      const std::vector<RunRecord>& held) {
  std::map<RunKey, std::size_t> index;
  for (std::size_t i = 0; i < plan.size(); ++i) index.emplace(plan[i], i);
  std::set<std::size_t> done;
  for (const auto& run : held) {
    const RunKey key = key_of(run);
    const auto it = index.find(key);
    if (it == index.end() || !shard.holds(it->second)) {
      throw ShardError(
          fmt::format("run {} is not in shard {} of this sweep", key.text(), shard.text()));
    }
    if (!done.insert(it->second).second)
      throw ShardError(fmt::format("run {} is there twice", key.text()));
  }
  std::vector<std::size_t> pending;
  for (std::size_t i = 0; i < plan.size(); ++i) {
    if (shard.holds(i) && !done.count(i)) pending.push_back(i);
  }
  return pending;
}

std::vector<RunRecord> merge_shards(const std::vector<RunKey>& plan,
                                    const std::vector<ShardRuns>& shards) {
  std::map<RunKey, std::size_t> index;
  for (std::size_t i = 0; i < plan.size(); ++i) index.emplace(plan[i], i);
  std::vector<std::optional<RunRecord>> merged(plan.size());
  std::vector<std::string> found_in(plan.size());
  for (const auto& shard : shards) {
    for (const auto& run : shard.runs) {
      const RunKey key = key_of(run);
      const auto it = index.find(key);
      if (it == index.end())
        throw ShardError(
            fmt::format("run {} in {} is not a run of the sweep", key.text(), shard.dir));
      if (merged[it->second]) {
        throw ShardError(fmt::format("run {} is there twice: in {} and in {}", key.text(),
                                     found_in[it->second], shard.dir));
      }
      merged[it->second] = run;
      found_in[it->second] = shard.dir;
    }
  }
  std::vector<RunRecord> runs;
  runs.reserve(plan.size());
  for (std::size_t i = 0; i < plan.size(); ++i) {
    if (!merged[i]) {
      std::string dirs;
      for (const auto& shard : shards) dirs += (dirs.empty() ? "" : ", ") + shard.dir;
      throw ShardError(fmt::format("run {} (index {}) is missing: none of {} holds it",
                                   plan[i].text(), i, dirs));
    }
    runs.push_back(std::move(*merged[i]));
  }
  return runs;
}

}  // namespace conicloc::eval
