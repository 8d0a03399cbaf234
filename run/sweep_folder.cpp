#include "run/sweep_folder.hpp"

#include <fmt/format.h>

#include <fstream>
#include <sstream>

#include "eval/robustness_report.hpp"
#include "eval/scale_report.hpp"
#include "eval/sweep_plan.hpp"
#include "io/input_error.hpp"
#include "io/tum_trajectory.hpp"
#include "run/sweep_plots.hpp"

namespace conicloc::run {
namespace {

namespace fs = std::filesystem;

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

}  // namespace

std::string absolute_map_path(const std::string& map) {
  return eval::is_generated_map(map) ? map : fs::absolute(map).lexically_normal().string();
}

bool SweepFolderInfo::operator==(const SweepFolderInfo& other) const {
  return map_path == other.map_path && shard.index == other.shard.index &&
         shard.count == other.shard.count &&
         metrics.max_time_gap_s == other.metrics.max_time_gap_s &&
         metrics.rpe_delta_m == other.metrics.rpe_delta_m;
}

std::string sweep_folder_spec_text(const eval::SweepSpec& spec) {
  eval::SweepSpec absolute = spec;
  for (auto& map : absolute.maps) map = absolute_map_path(map);
  return eval::sweep_file_text(absolute);
}

void write_sweep_folder(const fs::path& dir, const eval::SweepSpec& spec,
                        const SweepFolderInfo& info) {
  write_text_file(dir / "sweep.txt", sweep_folder_spec_text(spec));
  write_text_file(dir / "shard.txt",
                  fmt::format("# conicloc evaluate: the sweep of sweep.txt on this building, this "
                              "shard, these metric settings\nmap = {}\nshard = {}\n"
                              "max_time_gap_s = {}\nrpe_delta_m = {}\n",
                              absolute_map_path(info.map_path), info.shard.text(),
                              info.metrics.max_time_gap_s, info.metrics.rpe_delta_m));
}

std::optional<SweepFolderInfo> read_sweep_folder_info(const fs::path& dir) {
  const fs::path path = dir / "shard.txt";
  std::ifstream in(path);
  if (!in) return std::nullopt;
  SweepFolderInfo info;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    line = trim(line.substr(0, line.find('#')));
    if (line.empty()) continue;
    const auto equals = line.find('=');
    const std::string key = trim(line.substr(0, equals));
    const std::string value = equals == std::string::npos ? "" : trim(line.substr(equals + 1));
    try {
      if (key == "map") {
        info.map_path = value;
      } else if (key == "shard") {
        info.shard = eval::parse_shard(value);
      } else if (key == "max_time_gap_s") {
        info.metrics.max_time_gap_s = std::stod(value);
      } else if (key == "rpe_delta_m") {
        info.metrics.rpe_delta_m = std::stod(value);
      } else {
        throw std::invalid_argument("unknown key '" + key + "'");
      }
    } catch (const std::exception& e) {
      throw io::InputError(path.string(), "line " + std::to_string(number), e.what());
    }
  }
  return info;
}

void write_text_file(const fs::path& path, const std::string& text) {
  const fs::path partial = path.string() + ".partial";
  {
    std::ofstream out(partial);
    out << text;
    out.flush();
    if (!out) throw io::InputError(partial.string(), "", "cannot write");
  }
  std::error_code error;
  fs::rename(partial, path, error);
  if (error) throw io::InputError(path.string(), "", "cannot write: " + error.message());
}

std::string recording_file(const eval::RunRecord& run, const std::string& suffix) {
  return "runs/" + eval::recording_name(run.building, run.scenario, run.seed) + suffix;
}

void score_run(eval::RunRecord& run, const fs::path& dir, const eval::MetricsConfig& metrics) {
  const auto truth = io::read_tum((dir / recording_file(run, eval::kTruthSuffix)).string());
  const auto estimate = io::read_tum((dir / run.estimate_file).string());
  run.metrics = eval::evaluate_trajectory(truth, estimate, metrics);
  run.converged = run.metrics.convergence_time_s.has_value();
  run.time_to_10cm_s = eval::time_to_settle_s(run.metrics.errors, 0.10);
  run.time_to_50cm_s = eval::time_to_settle_s(run.metrics.errors, 0.50);
  const fs::path map_fit_path = dir / recording_file(run, eval::kMapFitSuffix);
  if (fs::exists(map_fit_path)) {
    const auto map_fit = io::read_tum(map_fit_path.string());
    // Both shares at the estimate's times: the map's pose there, as the truth is taken there.
    std::vector<io::StampedPose> map_fit_at_estimates;
    for (const io::StampedPose& e : estimate) {
      if (auto pose = eval::interpolate_pose(map_fit, e.time_s, metrics.max_time_gap_s))
        map_fit_at_estimates.push_back({e.time_s, *pose});
    }
    const eval::TrajectoryMetrics map_share =
        eval::evaluate_trajectory(truth, map_fit_at_estimates, metrics);
    const eval::TrajectoryMetrics own_share = eval::evaluate_trajectory(map_fit, estimate, metrics);
    run.map_fit_xy_rmse_m = map_share.ate_xy_m.rmse;
    run.ate_xy_rmse_to_map_fit_m = own_share.ate_xy_m.rmse;
    run.map_fit_heading_rmse_deg = map_share.heading_deg.rmse;
    run.heading_rmse_to_map_fit_deg = own_share.heading_deg.rmse;
  }
}

std::optional<Building> first_building(const std::vector<BuildingSource>& sources,
                                       const eval::SweepSpec& spec, const fs::path& buildings_dir) {
  for (const auto& source : sources) {
    for (const auto seed : spec.seeds) {
      try {
        return load_building(source, seed, buildings_dir);
      } catch (const std::exception&) {
        if (!source.per_seed()) break;  // the same file for every seed
      }
    }
  }
  return std::nullopt;
}

std::vector<eval::PlannedBuilding> planned_buildings(const std::vector<BuildingSource>& sources) {
  std::vector<eval::PlannedBuilding> planned;
  for (const auto& source : sources) planned.push_back({source.name, source.per_seed()});
  return planned;
}

void write_sweep_report(const std::string& command, const std::optional<Building>& plotted,
                        const std::vector<eval::RunRecord>& runs, const fs::path& out_dir) {
  std::vector<std::string> plots;
  if (!runs.empty() && plotted) plots = write_plots(*plotted, runs, out_dir);
  write_text_file(out_dir / "summary.md", eval::summary_markdown(runs, command, plots));
  write_text_file(out_dir / "robustness.md", fmt::format("# Robustness\n\nCommand: `{}`\n{}",
                                                         command, eval::robustness_markdown(runs)));
  write_text_file(out_dir / "cost_against_size.svg", eval::scale_svg(runs));
  write_text_file(out_dir / "scale.md",
                  fmt::format("# Cost against building size\n\nCommand: `{}`\n\n"
                              "![time per scan against floor area](cost_against_size.svg)\n{}",
                              command, eval::scale_markdown(runs)));
}

}  // namespace conicloc::run
