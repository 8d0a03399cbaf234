#include "tools/evaluate_sweep.hpp"

#include <spdlog/spdlog.h>

#include <filesystem>
#include <fstream>
#include <thread>

#include "eval/sweep_report.hpp"
#include "eval/sweep_scenario.hpp"
#include "io/indoorgml.hpp"
#include "io/input_error.hpp"
#include "io/map_export.hpp"
#include "io/pcap_writer.hpp"
#include "localizer/free_space.hpp"
#include "localizer/parallel_for.hpp"
#include "sensor/builtin_calibration.hpp"
#include "sim/simulation.hpp"
#include "tools/localize_run.hpp"

namespace conicloc::tools {
namespace {

namespace fs = std::filesystem;

struct Building {
  std::string name;  ///< file stem, unique within the sweep
  maps::PlaneMap map;
  bool two_sided_walls = false;
};

// One simulated recording, shared by every localizer configuration run on it.
struct Recording {
  std::string name;  ///< <building>-<scenario>-s<seed>
  std::string pcap_path;
  std::vector<io::StampedPose> truth;
  std::vector<io::StampedPose> odometry;
  double sensor_height_m = 0.8;
};

struct LocalizerSetting {
  std::string model;
  int particles = 0;
  int beams = 0;
};

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  out.flush();
  if (!out) throw io::InputError(path.string(), "", "cannot write");
}

std::vector<Building> load_buildings(const SweepOptions& options) {
  std::vector<Building> buildings;
  std::vector<std::string> paths{options.map_path};
  paths.insert(paths.end(), options.spec.maps.begin(), options.spec.maps.end());
  for (const auto& path : paths) {
    auto loaded = io::load_indoorgml(path);
    for (const auto& warning : loaded.report.warnings) spdlog::warn("{}: {}", path, warning);
    Building building;
    building.name = fs::path(path).stem().string();
    for (int k = 2; std::any_of(buildings.begin(), buildings.end(),
                                [&](const Building& b) { return b.name == building.name; });
         ++k) {
      building.name = fs::path(path).stem().string() + "-" + std::to_string(k);
    }
    building.two_sided_walls = loaded.report.two_sided_faces > 0;
    building.map = std::move(loaded.map);
    buildings.push_back(std::move(building));
  }
  return buildings;
}

// Every (model, particles, beams) of the sweep; conic-segment segments every return, so it runs
// once per particle count.
std::vector<LocalizerSetting> localizer_settings(const eval::SweepSpec& spec) {
  std::vector<LocalizerSetting> settings;
  for (const auto& model : spec.models) {
    for (const int particles : spec.particles) {
      if (model == "conic-segment") {
        settings.push_back({model, particles, 0});
        continue;
      }
      for (const int beams : spec.beams) settings.push_back({model, particles, beams});
    }
  }
  return settings;
}

Recording simulate(const Building& building, const eval::Scenario& scenario, std::uint64_t seed,
                   const eval::SweepSpec& spec, const fs::path& runs_dir) {
  sim::SimulationConfig config;
  config.seed = seed;
  config.duration_s = spec.duration_s;
  config.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  config.trajectory.style = scenario.handheld ? sim::MotionStyle::Handheld : sim::MotionStyle::Robot;
  if (!scenario.effects) {
    config.disable_effects();
  } else {
    config.effects.range_noise_m = scenario.range_noise_m;
    config.clutter.level = scenario.clutter_level;
    config.map_error_m = scenario.map_error_m;
  }
  sim::Simulation simulation(building.map, config);

  Recording recording;
  recording.name = building.name + "-" + scenario.name + "-s" + std::to_string(seed);
  recording.pcap_path = (runs_dir / (recording.name + ".pcap")).string();
  io::PcapWriter pcap(recording.pcap_path);
  simulation.run([&](const io::EncodedPacket& packet, double utc_time_s) {
    pcap.write_udp(packet.payload, utc_time_s);
  });
  pcap.close();
  recording.truth = simulation.truth();
  recording.odometry = simulation.odometry();
  io::write_tum((runs_dir / (recording.name + ".truth.tum")).string(), recording.truth);
  io::write_tum((runs_dir / (recording.name + ".odom.tum")).string(), recording.odometry);
  recording.sensor_height_m = config.trajectory.sensor_height_m >= 0.0
                                  ? config.trajectory.sensor_height_m
                                  : (scenario.handheld ? 1.4 : 0.8);
  return recording;
}

// The kidnap start: confident at a pose 3 m and 90° from the truth, over navigable floor when one
// of eight directions gives one.
localizer::Pose3 kidnapped_pose(const maps::PlaneMap& map, const localizer::Pose3& truth) {
  const localizer::FreeSpace free_space(map);
  const Eigen::Vector3d t = truth.translation();
  const double yaw = localizer::yaw_of(truth) + M_PI / 2.0;
  for (int k = 0; k < 8; ++k) {
    const double angle = k * M_PI / 4.0;
    const double x = t.x() + 3.0 * std::cos(angle);
    const double y = t.y() + 3.0 * std::sin(angle);
    if (free_space.cell_at(x, y, t.z()) >= 0) return localizer::make_pose(x, y, t.z(), yaw);
  }
  return localizer::make_pose(t.x() + 3.0, t.y(), t.z(), yaw);
}

FilterStart filter_start(const Building& building, const eval::Scenario& scenario,
                         const Recording& recording) {
  FilterStart start;
  const localizer::Pose3 first = recording.truth.front().pose;
  const Eigen::Vector3d t = first.translation();
  switch (scenario.start) {
    case eval::FilterStartMode::Global:
      start.global = true;
      break;
    case eval::FilterStartMode::Kidnap:
      start.pose = kidnapped_pose(building.map, first);
      start.sigma << 0.1, 0.1, 0.02, 0.01, 0.01, 2.0 * M_PI / 180.0;
      break;
    case eval::FilterStartMode::Tracking:
      start.pose = localizer::make_pose(t.x(), t.y(), t.z(), localizer::yaw_of(first));
      start.sigma << 0.2, 0.2, 0.02, 0.01, 0.01, 5.0 * M_PI / 180.0;
      break;
  }
  return start;
}

eval::RunRecord localize(const Building& building, const eval::Scenario& scenario,
                         std::uint64_t seed, const Recording& recording,
                         const LocalizerSetting& setting, const SweepOptions& options,
                         const fs::path& runs_dir) {
  eval::RunRecord record;
  record.building = building.name;
  record.scenario = scenario.name;
  record.seed = seed;
  record.model = setting.model;
  record.particles = setting.particles;
  record.beams = setting.beams;
  record.threads = localizer::resolve_thread_count(options.spec.threads);
  record.cores = static_cast<int>(std::thread::hardware_concurrency());

  LocalizeRunConfig run;
  run.pcap_path = recording.pcap_path;
  run.calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  auto& config = run.localizer;
  config.observation.model = setting.model;
  config.observation.conic_beam.beams.max_beams = static_cast<std::size_t>(setting.beams);
  config.observation.point_to_plane.beams.max_beams = static_cast<std::size_t>(setting.beams);
  const auto particles = static_cast<std::size_t>(setting.particles);
  config.filter.max_particles = particles;
  config.filter.initial_particles = particles;
  config.filter.min_particles = std::min(config.filter.min_particles, particles);
  config.motion.height_above_floor_m = recording.sensor_height_m;
  config.threads = options.spec.threads;
  config.seed = seed;
  run.two_sided_walls = building.two_sided_walls;
  run.odometry = recording.odometry;
  run.start = filter_start(building, scenario, recording);

  std::vector<io::StampedPose> estimate;
  double particle_sum = 0.0;
  const auto summary = run_localization(
      building.map, run, [&](double utc_s, const localizer::UpdateResult& result) {
        estimate.push_back({utc_s, result.pose});
        particle_sum += static_cast<double>(result.particles);
      });
  const std::string estimate_name = recording.name + "-" + setting.model + "-p" +
                                    std::to_string(setting.particles) + "-b" +
                                    std::to_string(setting.beams) + ".tum";
  io::write_tum((runs_dir / estimate_name).string(), estimate);
  record.estimate_file = "runs/" + estimate_name;
  record.metrics = eval::evaluate_trajectory(recording.truth, estimate, options.metrics);
  record.converged = record.metrics.convergence_time_s.has_value();
  record.scans = summary.scans;
  record.recoveries = summary.recoveries;
  record.time_per_scan_ms = summary.mean_time_ms();
  record.time_p95_ms = summary.quantile_time_ms(0.95);
  record.realtime_factor = summary.realtime_factor();
  record.mean_particles = summary.scans > 0 ? particle_sum / static_cast<double>(summary.scans) : 0;
  return record;
}

// The runs to show over time and over the plan: per model its largest configuration on the
// first recording of the given scenario.
std::vector<eval::RunRecord> showcase_runs(const std::vector<eval::RunRecord>& runs,
                                           const std::string& building,
                                           const std::string& scenario) {
  std::vector<eval::RunRecord> chosen;
  std::optional<std::uint64_t> seed;
  for (const auto& run : runs) {
    if (run.building != building || run.scenario != scenario || run.failed) continue;
    if (!seed) seed = run.seed;
    if (run.seed != *seed) continue;
    auto it = std::find_if(chosen.begin(), chosen.end(),
                           [&](const eval::RunRecord& c) { return c.model == run.model; });
    if (it == chosen.end()) {
      chosen.push_back(run);
    } else if (std::tie(run.particles, run.beams) > std::tie(it->particles, it->beams)) {
      *it = run;
    }
  }
  return chosen;
}

std::string trajectory_plan_svg(const Building& building, const std::vector<eval::RunRecord>& runs,
                                const fs::path& out_dir, const std::string& truth_path) {
  static const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e"};
  io::FloorPlanOptions options;
  options.show_navigation = false;
  const auto to_path = [](const std::vector<io::StampedPose>& poses) {
    std::vector<Eigen::Vector3d> points;
    for (const auto& p : poses) points.push_back(p.pose.translation());
    return points;
  };
  options.paths.push_back({.label = "truth",
                           .colour = "#222222",
                           .width_px = 2.4,
                           .dashed = false,
                           .points = to_path(io::read_tum(truth_path))});
  std::size_t k = 0;
  for (const auto& run : runs) {
    options.paths.push_back(
        {.label = fmt::format("{} ({} p)", run.model, run.particles),
         .colour = kColours[k++ % std::size(kColours)],
         .width_px = 1.4,
         .dashed = true,
         .points = to_path(io::read_tum((out_dir / run.estimate_file).string()))});
  }
  return io::render_floor_plan_svg(building.map, options);
}

void write_report(const SweepOptions& options, const std::vector<Building>& buildings,
                  const std::vector<eval::RunRecord>& runs, const fs::path& out_dir) {
  std::vector<std::string> plots;
  if (!runs.empty()) {
    write_text(out_dir / "pareto.svg", eval::pareto_svg(runs));
    plots.push_back("pareto.svg");
    const std::string building = runs.front().building;
    std::vector<std::string> scenarios;
    for (const auto& run : runs) {
      if (run.building == building &&
          std::find(scenarios.begin(), scenarios.end(), run.scenario) == scenarios.end())
        scenarios.push_back(run.scenario);
    }
    for (const auto& scenario : scenarios) {
      const auto shown = showcase_runs(runs, building, scenario);
      if (shown.empty()) continue;
      const std::string recording =
          building + "-" + scenario + "-s" + std::to_string(shown.front().seed);
      const std::string errors_name = "error_over_time_" + scenario + ".svg";
      write_text(out_dir / errors_name,
                 eval::error_over_time_svg(shown, "Horizontal error along " + recording));
      plots.push_back(errors_name);
      const auto it = std::find_if(buildings.begin(), buildings.end(),
                                   [&](const Building& b) { return b.name == building; });
      const std::string plan_name = "trajectory_" + scenario + ".svg";
      write_text(out_dir / plan_name,
                 trajectory_plan_svg(*it, shown, out_dir,
                                     (out_dir / "runs" / (recording + ".truth.tum")).string()));
      plots.push_back(plan_name);
    }
  }
  write_text(out_dir / "summary.md", eval::summary_markdown(runs, options.command, plots));
}

}  // namespace

int run_sweep(const SweepOptions& options) {
  const fs::path out_dir(options.out_dir);
  const fs::path runs_dir = out_dir / "runs";
  fs::create_directories(runs_dir);
  const auto buildings = load_buildings(options);
  const auto settings = localizer_settings(options.spec);
  const std::size_t total = buildings.size() * options.spec.scenarios.size() *
                            options.spec.seeds.size() * settings.size();
  spdlog::info("sweep '{}': {} runs ({} recordings x {} localizer settings) into {}",
               options.spec.name, total, total / std::max<std::size_t>(settings.size(), 1),
               settings.size(), out_dir.string());

  std::vector<eval::RunRecord> runs;
  int failed = 0;
  for (const auto& building : buildings) {
    for (const auto& scenario_name : options.spec.scenarios) {
      const eval::Scenario* scenario = eval::find_scenario(scenario_name);
      if (!scenario) throw std::invalid_argument("unknown scenario '" + scenario_name + "'");
      for (const auto seed : options.spec.seeds) {
        std::optional<Recording> recording;
        std::string simulation_error;
        try {
          recording = simulate(building, *scenario, seed, options.spec, runs_dir);
        } catch (const std::exception& e) {
          simulation_error = std::string("simulation: ") + e.what();
          spdlog::error("{} {} seed {}: {}", building.name, scenario_name, seed, simulation_error);
        }
        for (const auto& setting : settings) {
          eval::RunRecord record;
          try {
            if (!recording) throw std::runtime_error(simulation_error);
            record = localize(building, *scenario, seed, *recording, setting, options, runs_dir);
          } catch (const std::exception& e) {
            record = eval::RunRecord{};
            record.building = building.name;
            record.scenario = scenario_name;
            record.seed = seed;
            record.model = setting.model;
            record.particles = setting.particles;
            record.beams = setting.beams;
            record.failed = true;
            record.error = e.what();
            ++failed;
          }
          runs.push_back(record);
          spdlog::info(
              "[{}/{}] {} {} s{} {} p{} b{}: ATE xy {:.3f} m, heading {:.2f} deg, {:.1f} ms/scan, "
              "{}",
              runs.size(), total, building.name, scenario_name, seed, setting.model,
              setting.particles, setting.beams, record.metrics.ate_xy_m.rmse,
              record.metrics.heading_deg.rmse, record.time_per_scan_ms,
              record.failed ? "FAILED: " + record.error
                            : (record.converged ? "converged" : "not converged"));
          // Written after every run: a long sweep that is stopped keeps what it measured.
          write_text(out_dir / "runs.csv", eval::runs_csv(runs));
        }
        if (recording && !options.spec.keep_captures) fs::remove(recording->pcap_path);
      }
    }
  }
  write_report(options, buildings, runs, out_dir);
  spdlog::info("wrote {}/runs.csv, summary.md and plots", out_dir.string());
  return failed;
}

}  // namespace conicloc::tools
