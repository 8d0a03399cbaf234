#pragma once
// What a sweep's output folder holds besides the runs: the sweep itself (sweep.txt, a sweep file
// with every key, and shard.txt: the building given with --map, the shard, the metric settings),
// so a shard can be resumed and shards merged; how a run is scored from the files it leaves; and
// the report (summary.md, robustness.md, plots) written from the runs, the same for a whole sweep
// and for a merge of shards.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "eval/sweep_report.hpp"
#include "eval/sweep_shard.hpp"
#include "eval/sweep_spec.hpp"
#include "eval/trajectory_metrics.hpp"
#include "run/sweep_buildings.hpp"

namespace conicloc::run {

/// shard.txt: what, besides the sweep file, makes two shards parts of one sweep.
struct SweepFolderInfo {
  std::string map_path;  ///< --map, absolute (or generated:…)
  eval::Shard shard;     ///< 1/1 for a whole sweep
  eval::MetricsConfig metrics;
  bool operator==(const SweepFolderInfo& other) const;
};

/// A map entry as the folder keeps it: a file's absolute path, or `generated:…` as it is.
std::string absolute_map_path(const std::string& map);

/// Writes `dir`/sweep.txt (the spec with absolute map paths) and `dir`/shard.txt.
void write_sweep_folder(const std::filesystem::path& dir, const eval::SweepSpec& spec,
                        const SweepFolderInfo& info);

/// The text write_sweep_folder() puts in sweep.txt.
std::string sweep_folder_spec_text(const eval::SweepSpec& spec);

/// Reads `dir`/shard.txt; empty when the folder has none. Throws io::InputError for a bad line.
std::optional<SweepFolderInfo> read_sweep_folder_info(const std::filesystem::path& dir);

/// Writes `text` to `path` through a temporary file renamed over it, so a stopped process leaves
/// the old or the new text, never a cut one. Throws io::InputError.
void write_text_file(const std::filesystem::path& path, const std::string& text);

/// A file of a run's recording, relative to the sweep folder: `runs/<recording name><suffix>`
/// (eval::kTruthSuffix, eval::kMapFitSuffix, ...).
std::string recording_file(const eval::RunRecord& run, const std::string& suffix);

/// Scores a run from its truth and estimate files in `dir` (metrics, converged, time_to_10cm_s),
/// and from its map-fit file where there is one (RunRecord::map_fit_xy_rmse_m and the others):
/// a merge rescores from the same files the run was scored from, so the figures are the same.
void score_run(eval::RunRecord& run, const std::filesystem::path& dir,
               const eval::MetricsConfig& metrics);

/// The sweep's first building that loads (buildings in order, each with the sweep's seeds in
/// order): the one whose recordings are plotted. Empty when none loads.
std::optional<Building> first_building(const std::vector<BuildingSource>& sources,
                                       const eval::SweepSpec& spec,
                                       const std::filesystem::path& buildings_dir);

/// The planned buildings of the sweep's building list.
std::vector<eval::PlannedBuilding> planned_buildings(const std::vector<BuildingSource>& sources);

/// Writes summary.md, robustness.md and the plots of `plotted` (when given) into `out_dir`.
void write_sweep_report(const std::string& command, const std::optional<Building>& plotted,
                        const std::vector<eval::RunRecord>& runs,
                        const std::filesystem::path& out_dir);

}  // namespace conicloc::run
