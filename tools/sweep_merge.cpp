#include "tools/sweep_merge.hpp"

#include <spdlog/spdlog.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "eval/runs_csv_reader.hpp"
#include "eval/sweep_plan.hpp"
#include "eval/sweep_shard.hpp"
#include "run/sweep_buildings.hpp"
#include "run/sweep_folder.hpp"

namespace conicloc::tools {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw eval::ShardError(path.string() + ": cannot read it; is this a shard's folder?");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The files of `from` (recursively) that `to` has not got yet; a recording that several shards
// simulated is the same file in each of them.
void copy_missing(const fs::path& from, const fs::path& to) {
  if (!fs::is_directory(from)) return;
  for (const auto& entry : fs::recursive_directory_iterator(from)) {
    const fs::path target = to / fs::relative(entry.path(), from);
    if (entry.is_directory()) {
      fs::create_directories(target);
    } else if (!fs::exists(target)) {
      fs::create_directories(target.parent_path());
      fs::copy_file(entry.path(), target);
    }
  }
}

}  // namespace

int merge_sweep(const MergeOptions& options) {
  if (options.shard_dirs.empty()) throw eval::ShardError("--merge needs the shards' folders");
  const fs::path out_dir(options.out_dir);
  for (const auto& dir : options.shard_dirs) {
    if (fs::exists(out_dir) && fs::exists(dir) && fs::equivalent(dir, out_dir))
      throw eval::ShardError("--out " + options.out_dir +
                             " is one of the shards: give a new folder");
  }
  // The sweep, as the first shard has it; every other shard must have the same.
  const std::string& first = options.shard_dirs.front();
  const std::string spec_text = slurp(fs::path(first) / "sweep.txt");
  const auto info = run::read_sweep_folder_info(first);
  if (!info) throw eval::ShardError(first + " has no shard.txt: is this a shard's folder?");
  std::vector<eval::ShardRuns> shards;
  for (const auto& dir : options.shard_dirs) {
    const auto other = run::read_sweep_folder_info(dir);
    if (!other) throw eval::ShardError(dir + " has no shard.txt: is this a shard's folder?");
    if (slurp(fs::path(dir) / "sweep.txt") != spec_text || other->map_path != info->map_path ||
        other->shard.count != info->shard.count ||
        other->metrics.max_time_gap_s != info->metrics.max_time_gap_s ||
        other->metrics.rpe_delta_m != info->metrics.rpe_delta_m) {
      throw eval::ShardError(dir + " is a shard of another sweep than " + first +
                             " (their sweep.txt or shard.txt differ)");
    }
    const fs::path csv = fs::path(dir) / "runs.csv";
    auto read = eval::read_runs_csv(slurp(csv), csv.string());
    if (read.dropped_partial_line)
      spdlog::warn("{}: the last line was cut short; resume that shard", csv.string());
    shards.push_back({dir, std::move(read.runs)});
  }
  const auto spec = eval::read_sweep_file((fs::path(first) / "sweep.txt").string());
  std::vector<std::string> maps{info->map_path};
  maps.insert(maps.end(), spec.maps.begin(), spec.maps.end());
  const auto sources = run::building_sources(maps);
  const auto plan = eval::plan_runs(run::planned_buildings(sources), spec);
  auto runs = eval::merge_shards(plan, shards);
  spdlog::info("{} shards of {}: {} runs, each once", shards.size(), info->shard.count,
               runs.size());

  fs::create_directories(out_dir / "runs");
  for (const auto& dir : options.shard_dirs) {
    copy_missing(fs::path(dir) / "runs", out_dir / "runs");
    copy_missing(fs::path(dir) / "buildings", out_dir / "buildings");
  }
  int failed = 0;
  for (auto& record : runs) {
    if (record.failed) {
      ++failed;
      continue;
    }
    run::score_run(record, out_dir, info->metrics);
  }
  run::write_sweep_folder(out_dir, spec, {info->map_path, eval::Shard{}, info->metrics});
  run::write_text_file(out_dir / "runs.csv", eval::runs_csv(runs));
  const auto plotted = run::first_building(sources, spec, out_dir / "buildings");
  if (plotted) {
    for (const auto& warning : plotted->warnings) spdlog::warn("{}", warning);
  }
  run::write_sweep_report(options.command, plotted, runs, out_dir);
  spdlog::info("wrote {}/runs.csv, summary.md, robustness.md and plots", out_dir.string());
  return failed;
}

}  // namespace conicloc::tools
