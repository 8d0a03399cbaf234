#pragma once
// One simulated recording: a trajectory through the building, the world the sensor sees (map with
// errors, clutter, people), the VLP-16 fired along it, packets handed to a sink, ground truth and
// odometry. All randomness comes from `seed`: the same configuration gives the same bytes.
//
// Time: t = 0 is the first firing. Capture (pcap) time = start_epoch_s + t (UTC seconds); the
// device clock stamps microseconds past the UTC hour, so a start a few seconds before the hour
// simulates the roll-over. Truth and odometry are stamped in UTC seconds like the capture.
// Rotation: the head starts at Velodyne azimuth α = 0 (θ = 0), so scan k starts at t = k·60/rpm;
// the truth holds the pose at each scan start (or at each packet's first firing).

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <random>
#include <vector>

#include "io/packet_encoder.hpp"
#include "io/tum_trajectory.hpp"
#include "maps/plane_map.hpp"
#include "sensor/laser_calibration.hpp"
#include "sim/clutter.hpp"
#include "sim/navigation_route.hpp"
#include "sim/odometry_drift.hpp"
#include "sim/trajectory.hpp"
#include "sim/vlp16_simulator.hpp"
#include "sim/world.hpp"

namespace conicloc::sim {

struct SimulationConfig {
  std::uint64_t seed = 1;
  /// Seeds the per-return draws alone (range noise, intensity jitter, dropouts) in place of
  /// `seed`: the same route, world and calibration errors with the noise drawn anew, so that a
  /// Monte Carlo over it shows how far the noise alone moves an estimate.
  std::optional<std::uint64_t> noise_seed;
  double duration_s = 10.0;  ///< ≤ 0: the whole trajectory (waypoint files), else this long
  std::vector<Waypoint> waypoints;  ///< empty: a route along the navigation graph
  /// length_m ≤ 0 (the default): long enough for the duration at cruise speed, with a margin
  /// for the slowing at doors and turns.
  RouteConfig route = [] {
    RouteConfig automatic;
    automatic.length_m = 0.0;
    return automatic;
  }();
  TrajectoryConfig trajectory;
  sensor::SensorModel model = sensor::SensorModel::VLP16;
  SensorConfig sensor;
  SensorEffects effects;
  double map_error_m = 0.02;  ///< σ of wall shifts and tilts (0: the world is the map)
  ClutterConfig clutter;
  OdometryConfig odometry;
  double start_epoch_s = 1767225600.0;  ///< 2026-01-01T00:00:00Z
  bool truth_per_packet = false;
  int threads = 1;  ///< ray casting threads; the output does not depend on it
  /// A second sensor on the carrier (two sensors in one capture), at T_first_second in the first
  /// sensor's frame: the same model, settings and effects, its own calibration errors, fired at
  /// the same times; its packets go to run()'s second sink. The first sensor's bytes are the same
  /// with or without it.
  std::optional<Eigen::Isometry3d> second_sensor;

  /// Every effect off: exact ranges (still 2 mm in the packet), the world is the map.
  void disable_effects();
};

struct SimulationStats {
  SensorStats sensor;
  std::uint64_t packets = 0;
  std::uint64_t sequences = 0;
  int furniture_boxes = 0;
  int people = 0;
  double path_length_m = 0.0;
};

using PacketSink = std::function<void(const io::EncodedPacket& packet, double utc_time_s)>;

class Simulation {
 public:
  /// Plans the trajectory and builds the world. Throws std::invalid_argument for an unusable
  /// configuration (rpm outside 300..1200, no route, non-positive speed).
  Simulation(const maps::PlaneMap& map, SimulationConfig config);
  Simulation(const Simulation&) = delete;  // the sensor refers to world_
  Simulation& operator=(const Simulation&) = delete;

  /// Fires the sensor for the whole duration, handing every packet to `sink` and, with a second
  /// sensor configured, its packets to `second_sink`; the two streams interleave in time order
  /// (both fire on one schedule: each first-sensor packet, then the second's of the same time).
  /// The stats count both sensors.
  SimulationStats run(const PacketSink& sink, const PacketSink& second_sink = {});

  /// Ground truth T_map_sensor: one pose per scan start and one at the end of the capture (or one
  /// per packet), UTC-stamped. The localizer reports each scan at its end: the last scan's pose
  /// needs the truth at the capture's end, not the last scan start's.
  std::vector<io::StampedPose> truth() const;
  /// Drifting odometry, UTC-stamped.
  std::vector<io::StampedPose> odometry() const;

  const Trajectory& trajectory() const { return trajectory_; }
  const World& world() const { return world_; }
  const Vlp16Simulator& sensor() const { return *simulator_; }
  /// The second sensor (SimulationConfig::second_sensor), or nullptr.
  const Vlp16Simulator* second_sensor() const { return second_simulator_.get(); }
  const SimulationConfig& config() const { return config_; }
  double duration_s() const { return duration_s_; }
  /// Device clock of t = 0: seconds past the UTC hour of the start epoch.
  double device_time_offset_s() const;

 private:
  SimulationConfig config_;
  std::mt19937_64 odometry_rng_;
  std::uint64_t packet_seed_ = 0;
  Trajectory trajectory_;
  World world_;
  std::unique_ptr<Vlp16Simulator> simulator_;
  std::unique_ptr<Vlp16Simulator> second_simulator_;
  double duration_s_ = 0.0;
  int furniture_boxes_ = 0;
  std::vector<double> packet_times_s_;  ///< filled by run(), for per-packet truth
};

}  // namespace conicloc::sim
