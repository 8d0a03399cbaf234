#pragma once
// A simulated capture localized through the library, as `conicloc simulate` and `conicloc
// localize` do it with their defaults: for tests of what the filter makes of a recording (the
// command line has tests of its own).

#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "io/indoorgml.hpp"
#include "io/pcap_writer.hpp"
#include "io/tum_trajectory.hpp"
#include "run/localize_run.hpp"
#include "sensor/builtin_calibration.hpp"
#include "sim/simulation.hpp"

namespace conicloc::test {

/// A recording as `conicloc simulate --out PCAP --truth … --odom …` writes it: the truth and
/// odometry are what its TUM files hold (rounded to their digits), as a test of the binary read
/// them.
struct SimulatedCapture {
  std::string pcap_path;
  std::vector<io::StampedPose> truth;
  std::vector<io::StampedPose> odometry;
};

/// Simulates `config` in `map` (on every core, as `conicloc simulate`) into `pcap_path`, with
/// the truth and odometry beside it (.truth.tum, .odom.tum).
inline SimulatedCapture simulate_capture(const maps::PlaneMap& map, sim::SimulationConfig config,
                                         const std::filesystem::path& pcap_path) {
  config.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  sim::Simulation simulation(map, config);
  io::PcapWriter pcap(pcap_path.string());
  simulation.run([&](const io::EncodedPacket& packet, double utc_time_s) {
    pcap.write_udp(packet.payload, utc_time_s);
  });
  pcap.close();
  std::filesystem::path truth_path = pcap_path, odometry_path = pcap_path;
  truth_path.replace_extension(".truth.tum");
  odometry_path.replace_extension(".odom.tum");
  io::write_tum(truth_path.string(), simulation.truth());
  io::write_tum(odometry_path.string(), simulation.odometry());
  return {pcap_path.string(), io::read_tum(truth_path.string()),
          io::read_tum(odometry_path.string())};
}

/// A number as `localize --init` text carries it (test/cli_run.hpp's init_argument: 6 decimals).
inline double as_init_text(double value) {
  return std::stod(std::to_string(value));
}

/// What `conicloc localize --pcap PCAP --init X,Y,Z,YAW_DEG` runs on `loaded` without other
/// options: the VLP-16's table, the default localizer, a start around the level pose at the first
/// true pose (as --init's text gives it) with σ 0.2 m, 0.2 m, 5°.
inline run::LocalizeRunConfig localize_defaults(const io::LoadedMap& loaded,
                                                const SimulatedCapture& capture) {
  run::LocalizeRunConfig config;
  config.pcap_path = capture.pcap_path;
  config.calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  config.localizer.motion.height_above_floor_m = 0.8;  // --height
  config.two_sided_walls = loaded.report.two_sided_faces > 0;
  const localizer::Pose3& first = capture.truth.front().pose;
  const Eigen::Vector3d t = first.translation();
  const double yaw_deg = as_init_text(localizer::yaw_of(first) * 180.0 / M_PI);
  config.start =
      run::start_around(localizer::make_pose(as_init_text(t.x()), as_init_text(t.y()),
                                             as_init_text(t.z()), yaw_deg * M_PI / 180.0),
                        0.2, 0.2, 5.0 * M_PI / 180.0);
  return config;
}

/// The estimate of every localized scan, and whether the filter recovered (restarted) there.
struct LocalizedRun {
  std::vector<io::StampedPose> estimate;
  std::vector<bool> recovered;
};

inline LocalizedRun localize(const maps::PlaneMap& map, const run::LocalizeRunConfig& config) {
  LocalizedRun result;
  run::run_localization(map, config, [&](double utc_s, const localizer::UpdateResult& update) {
    result.estimate.push_back({utc_s, update.pose});
    result.recovered.push_back(update.recovered);
  });
  return result;
}

}  // namespace conicloc::test
