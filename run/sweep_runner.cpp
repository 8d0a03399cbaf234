#include "run/sweep_runner.hpp"

#include <algorithm>
#include <cassert>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "eval/lost_alarms.hpp"
#include "eval/robustness_report.hpp"
#include "eval/runs_csv_reader.hpp"
#include "eval/sweep_plan.hpp"
#include "parallel/parallel_for.hpp"
#include "run/sweep_buildings.hpp"
#include "run/sweep_folder.hpp"
#include "run/sweep_run.hpp"

namespace conicloc::run {
namespace {

namespace fs = std::filesystem;

using eval::LocalizerSetting;

// The fields every run's record has, whether it ran or failed.
eval::RunRecord run_record(const std::string& building, const eval::Scenario& scenario,
                           std::uint64_t seed, const LocalizerSetting& setting) {
  eval::RunRecord record;
  record.building = building;
  record.scenario = scenario.name;
  record.seed = seed;
  record.model = setting.model;
  record.particles = setting.particles;
  record.beams = setting.beams;
  record.odometry = scenario.odometry;
  return record;
}

eval::RunRecord localize(const Building& building, const eval::Scenario& scenario,
                         std::uint64_t seed, const SweepRecording& recording,
                         const LocalizerSetting& setting, const SweepOptions& options,
                         const fs::path& runs_dir) {
  eval::RunRecord record = run_record(building.name, scenario, seed, setting);
  record.building_group = building.group;
  record.threads = conicloc::resolve_thread_count(options.spec.threads);
  record.cores = static_cast<int>(std::thread::hardware_concurrency());

  const SweepRunResult result = localize_recording(building.map, building.two_sided_walls, scenario,
                                                   seed, recording, setting, options.spec.threads);
  const std::string estimate_name = recording.name + "-" + setting.model + "-p" +
                                    eval::setting_text(setting.particles) + "-b" +
                                    eval::setting_text(setting.beams) + ".tum";
  io::write_tum((runs_dir / estimate_name).string(), result.estimate);
  record.estimate_file = "runs/" + estimate_name;
  // From the files, as a merge of shards scores it again.
  score_run(record, runs_dir.parent_path(), options.metrics);
  record.scans = result.summary.scans;
  record.recoveries = result.summary.recoveries;
  record.time_per_scan_ms = result.summary.mean_time_ms();
  record.time_p95_ms = result.summary.quantile_time_ms(0.95);
  record.realtime_factor = result.summary.realtime_factor();
  record.mean_particles = result.mean_particles;
  record.capture_s = result.summary.last_time_s - result.summary.first_time_s;
  record.false_alarms =
      eval::count_false_alarms(recording.truth, result.alarms, options.metrics.max_time_gap_s,
                               eval::RobustnessTargets{}.lost_xy_m);
  record.storeys = static_cast<int>(building.map.storeys.size());
  record.planes = building.map.polygons.size();
  record.floor_area_m2 = building.floor_area_m2;
  record.start_time_ms = result.summary.start_time_ms;
  record.search_scans = result.search_times_ms.size();
  record.search_time_mean_ms = mean_of(result.search_times_ms);
  record.search_time_max_ms = max_of(result.search_times_ms);
  record.tracking_time_mean_ms = mean_of(result.tracking_times_ms);
  return record;
}

std::string slurp_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

eval::RunRecord failed_record(const std::string& building, const eval::Scenario& scenario,
                              std::uint64_t seed, const LocalizerSetting& setting,
                              const std::string& error) {
  eval::RunRecord record = run_record(building, scenario, seed, setting);
  record.failed = true;
  record.error = error;
  return record;
}

// The runs a shard's runs.csv already holds (none for a whole sweep, which starts afresh).
std::vector<eval::RunRecord> held_runs(const SweepOptions& options, const fs::path& out_dir,
                                       const SweepFolderInfo& info, const SweepProgress& progress) {
  if (!options.shard) return {};
  const auto existing = read_sweep_folder_info(out_dir);
  if (existing && (!(*existing == info) ||
                   slurp_file(out_dir / "sweep.txt") != sweep_folder_spec_text(options.spec))) {
    throw eval::ShardError(out_dir.string() +
                           " holds another sweep or shard (see its sweep.txt and shard.txt): "
                           "give a new --out");
  }
  const fs::path csv = out_dir / "runs.csv";
  if (!fs::exists(csv)) return {};
  if (!existing) throw eval::ShardError(csv.string() + " is not from a shard: give a new --out");
  auto held = eval::read_runs_csv(slurp_file(csv), csv.string());
  if (held.dropped_partial_line && progress.warning)
    progress.warning(csv.string() + ": the last line was cut short; its run is made again");
  return held.runs;
}

}  // namespace

SweepResult run_sweep(const SweepOptions& options, const SweepProgress& progress) {
  const auto warn = [&](const std::string& message) {
    if (progress.warning) progress.warning(message);
  };
  const auto fail = [&](const std::string& message) {
    if (progress.error) progress.error(message);
  };
  const fs::path out_dir(options.out_dir);
  const fs::path runs_dir = out_dir / "runs";
  for (const auto& warning : options.spec.warnings) warn(warning);
  std::vector<std::string> maps{options.map_path};
  maps.insert(maps.end(), options.spec.maps.begin(), options.spec.maps.end());
  auto sources = building_sources(maps);
  if (sources.front().kind.empty()) sources.front().load = options.map_options;
  std::vector<const eval::Scenario*> scenarios;
  for (const auto& name : options.spec.scenarios) {
    scenarios.push_back(eval::find_scenario(name));
    if (!scenarios.back()) throw std::invalid_argument("unknown scenario '" + name + "'");
  }
  const auto settings = eval::localizer_settings(options.spec);
  const auto plan = eval::plan_runs(planned_buildings(sources), options.spec);
  const SweepFolderInfo info{absolute_map_path(options.map_path),
                             options.shard.value_or(eval::Shard{}), options.metrics};

  std::vector<eval::RunRecord> runs = held_runs(options, out_dir, info, progress);
  const auto pending = eval::pending_runs(plan, info.shard, runs);
  fs::create_directories(runs_dir);
  write_sweep_folder(out_dir, options.spec, info);
  std::vector<bool> todo(plan.size(), false);
  for (const auto i : pending) todo[i] = true;
  const auto any_todo = [&](std::size_t from, std::size_t count) {
    return std::any_of(todo.begin() + static_cast<std::ptrdiff_t>(from),
                       todo.begin() + static_cast<std::ptrdiff_t>(from + count),
                       [](bool t) { return t; });
  };
  if (progress.started) {
    progress.started({.runs = plan.size(),
                      .recordings = plan.size() / std::max<std::size_t>(settings.size(), 1),
                      .settings = settings.size(),
                      .held = runs.size(),
                      .to_make = pending.size()});
  }
  const std::size_t share = runs.size() + pending.size();

  std::optional<Building> plotted;  // the first building loaded: its recordings are plotted
  int failed = 0;
  std::size_t index = 0;  // of the run in the plan
  for (const auto& source : sources) {
    // Loaded once for every seed, or (generated per seed) drawn anew for each and then dropped.
    std::optional<Building> kept;
    for (const auto seed : options.spec.seeds) {
      if (!any_todo(index, scenarios.size() * settings.size())) {
        index += scenarios.size() * settings.size();
        continue;
      }
      std::optional<Building> drawn;
      std::string building_error;
      try {
        std::optional<Building>& slot = source.per_seed() ? drawn : kept;
        if (!slot) {
          slot = load_building(source, seed, out_dir / "buildings");
          for (const auto& warning : slot->warnings) warn(warning);
        }
      } catch (const std::exception& e) {
        building_error = std::string("building: ") + e.what();
        fail(source.map + " seed " + std::to_string(seed) + ": " + building_error);
      }
      const Building* building =
          source.per_seed() ? (drawn ? &*drawn : nullptr) : (kept ? &*kept : nullptr);
      if (building && !plotted) plotted = *building;
      const std::string building_name = eval::building_name({source.name, source.per_seed()}, seed);
      for (const eval::Scenario* scenario : scenarios) {
        if (!any_todo(index, settings.size())) {
          index += settings.size();
          continue;
        }
        std::optional<SweepRecording> recording;
        std::string simulation_error = building_error;
        if (building) {
          try {
            recording = simulate_recording(building->map, building->name, *scenario, seed,
                                           options.spec.duration_s, runs_dir);
          } catch (const std::exception& e) {
            simulation_error = std::string("simulation: ") + e.what();
            fail(building_name + " " + scenario->name + " seed " + std::to_string(seed) + ": " +
                 simulation_error);
          }
        }
        for (const auto& setting : settings) {
          if (!todo[index++]) continue;
          eval::RunRecord record;
          try {
            if (!recording) throw std::runtime_error(simulation_error);
            record = localize(*building, *scenario, seed, *recording, setting, options, runs_dir);
          } catch (const std::exception& e) {
            record = failed_record(building_name, *scenario, seed, setting, e.what());
            if (building) record.building_group = building->group;
            ++failed;
          }
          assert(eval::key_of(record) == plan[index - 1]);
          runs.push_back(record);
          // Written after every run: a long sweep that is stopped keeps what it measured, and a
          // stopped shard resumes from it.
          write_text_file(out_dir / "runs.csv", eval::runs_csv(runs));
          if (progress.run_done) {
            progress.run_done({.done = runs.size(),
                               .share = share,
                               .building = building_name,
                               .scenario = scenario,
                               .seed = seed,
                               .setting = setting,
                               .record = &runs.back()});
          }
        }
        if (recording && !options.spec.keep_captures) fs::remove(recording->pcap_path);
      }
    }
  }
  if (options.shard) {
    write_text_file(out_dir / "runs.csv", eval::runs_csv(runs));
  } else {
    write_sweep_report(options.command, plotted, runs, out_dir);
  }
  return {std::move(runs), failed};
}

}  // namespace conicloc::run
