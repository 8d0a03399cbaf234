#include "run/sweep_run.hpp"

#include <algorithm>
#include <cmath>
#include <thread>

#include "eval/sweep_plan.hpp"
#include "io/pcap_writer.hpp"
#include "localizer/filter/free_space.hpp"
#include "localizer/models/observation_factory.hpp"
#include "sensor/builtin_calibration.hpp"
#include "sim/map_fit.hpp"
#include "sim/simulation.hpp"

namespace conicloc::run {
namespace {

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

}  // namespace

SweepRecording simulate_recording(const maps::PlaneMap& map, const std::string& building_name,
                                  const eval::Scenario& scenario, std::uint64_t seed,
                                  double duration_s, const std::filesystem::path& runs_dir) {
  sim::SimulationConfig config;
  config.seed = seed;
  config.duration_s = duration_s;
  config.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  config.trajectory.style =
      scenario.handheld ? sim::MotionStyle::Handheld : sim::MotionStyle::Robot;
  if (!scenario.effects) {
    config.disable_effects();
  } else {
    config.effects.range_noise_m = scenario.range_noise_m;
    config.clutter.level = scenario.clutter_level;
    config.map_error_m = scenario.map_error_m;
  }
  sim::Simulation simulation(map, config);

  SweepRecording recording;
  recording.name = eval::recording_name(building_name, scenario.name, seed);
  recording.pcap_path = (runs_dir / (recording.name + eval::kCaptureSuffix)).string();
  io::PcapWriter pcap(recording.pcap_path);
  simulation.run([&](const io::EncodedPacket& packet, double utc_time_s) {
    pcap.write_udp(packet.payload, utc_time_s);
  });
  pcap.close();
  recording.truth = simulation.truth();
  recording.odometry = simulation.odometry();
  io::write_tum((runs_dir / (recording.name + eval::kTruthSuffix)).string(), recording.truth);
  io::write_tum((runs_dir / (recording.name + eval::kOdometrySuffix)).string(), recording.odometry);
  if (config.map_error_m > 0.0) {  // what the map allows: scored beside the truth (score_run)
    sim::MapFitConfig fit;
    fit.threads = config.threads;
    io::write_tum(
        (runs_dir / (recording.name + eval::kMapFitSuffix)).string(),
        sim::map_fit_poses(map, simulation.world(), sensor::builtin_calibration(config.model),
                           recording.truth, fit));
  }
  recording.sensor_height_m = config.trajectory.sensor_height_m >= 0.0
                                  ? config.trajectory.sensor_height_m
                                  : (scenario.handheld ? 1.4 : 0.8);
  return recording;
}

FilterStart sweep_filter_start(const maps::PlaneMap& map, eval::FilterStartMode mode,
                               const localizer::Pose3& first_truth) {
  const Eigen::Vector3d t = first_truth.translation();
  switch (mode) {
    case eval::FilterStartMode::Global:
      return {.global = true};
    case eval::FilterStartMode::Kidnap:
      return start_around(kidnapped_pose(map, first_truth), 0.1, 0.1, 2.0 * M_PI / 180.0);
    case eval::FilterStartMode::Tracking:
      break;
  }
  return start_around(localizer::make_pose(t.x(), t.y(), t.z(), localizer::yaw_of(first_truth)),
                      0.2, 0.2, 5.0 * M_PI / 180.0);
}

SweepRunResult localize_recording(const maps::PlaneMap& map, bool two_sided_walls,
                                  const eval::Scenario& scenario, std::uint64_t seed,
                                  const SweepRecording& recording,
                                  const eval::LocalizerSetting& setting, int threads) {
  LocalizeRunConfig run;
  run.pcap_path = recording.pcap_path;
  run.calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  auto& config = run.localizer;
  config.observation.model = setting.model;
  // `default` keeps LocalizerConfig's values: what `conicloc localize` runs without options.
  const auto& model = localizer::observation_model(setting.model);
  if (setting.beams != eval::kDefaultSetting && model.max_beams) {
    model.max_beams(config.observation) = static_cast<std::size_t>(setting.beams);
  }
  if (setting.particles != eval::kDefaultSetting) {
    const auto particles = static_cast<std::size_t>(setting.particles);
    config.filter.max_particles = particles;
    config.filter.initial_particles = particles;
    config.filter.min_particles = std::min(config.filter.min_particles, particles);
  }
  config.motion.height_above_floor_m = recording.sensor_height_m;
  config.threads = threads;
  config.seed = seed;
  run.two_sided_walls = two_sided_walls;
  if (scenario.odometry) run.odometry = recording.odometry;
  run.start = sweep_filter_start(map, scenario.start, recording.truth.front().pose);

  SweepRunResult result;
  double particle_sum = 0.0;
  SearchPhase phase(scenario.start == eval::FilterStartMode::Global);
  result.summary =
      run_localization(map, run, [&](double utc_s, const localizer::UpdateResult& update) {
        result.estimate.push_back({utc_s, update.pose});
        if (update.recovered) result.alarms.push_back({utc_s, update.pose});
        particle_sum += static_cast<double>(update.particles);
        (phase.add(update.status) ? result.search_times_ms : result.tracking_times_ms)
            .push_back(update.run_time_ms);
      });
  const std::size_t scans = result.summary.scans;
  result.mean_particles = scans > 0 ? particle_sum / static_cast<double>(scans) : 0;
  return result;
}

}  // namespace conicloc::run
