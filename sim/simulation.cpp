#include "sim/simulation.hpp"

#include <array>
#include <cmath>
#include <optional>
#include <random>
#include <stdexcept>

#include "parallel/parallel_for.hpp"
#include "sensor/builtin_calibration.hpp"
#include "sim/floor_surface.hpp"
#include "sim/map_errors.hpp"
#include "sim/navigation_geometry.hpp"

namespace conicloc::sim {
namespace {

constexpr double kSequencePeriod_s = 55.296e-6;  // VLP-16 manual: one firing sequence

// Independent streams for each part, drawn in a fixed order from the seed, so switching one
// effect off does not change the others (e.g. the same trajectory with and without clutter).
struct Streams {
  std::mt19937_64 route, trajectory, map, calibration, clutter, odometry, second_calibration;
  std::uint64_t packets;
  explicit Streams(std::uint64_t seed) {
    std::mt19937_64 master(seed);
    route.seed(master());
    trajectory.seed(master());
    map.seed(master());
    calibration.seed(master());
    clutter.seed(master());
    odometry.seed(master());
    packets = master();
    second_calibration.seed(master());  // drawn last: a second sensor changes no other stream
  }
};

Trajectory plan_trajectory(const maps::PlaneMap& map, const SimulationConfig& config,
                           Streams& streams) {
  if (!(config.trajectory.speed_mps > 0.0)) throw std::invalid_argument("speed must be > 0");
  std::vector<Waypoint> waypoints = config.waypoints;
  if (waypoints.empty()) {
    RouteConfig route = config.route;
    if (route.length_m <= 0.0) {
      route.length_m = config.trajectory.speed_mps * std::max(config.duration_s, 1.0) * 1.5 + 10.0;
    }
    waypoints = plan_navigation_route(map, route, streams.route).waypoints;
  }
  if (waypoints.empty()) throw std::invalid_argument("no waypoints to follow");
  // The route interpolates z linearly between waypoints; the carrier rides on the real floor
  // (a stair's landings and flight), so the sensor keeps its height above it.
  const FloorSurface ground(map.polygons);
  return Trajectory(waypoints, config.trajectory, streams.trajectory,
                    [&ground](const Eigen::Vector3d& p) { return ground.height_under(p); });
}

World build_world(const maps::PlaneMap& map, const SimulationConfig& config,
                  const Trajectory& trajectory, Streams& streams, int& boxes) {
  std::vector<maps::PlanarPolygon> polygons =
      perturb_walls(map.polygons, config.map_error_m, streams.map);
  std::vector<SurfaceMaterial> materials;
  for (const auto& polygon : polygons) {
    // Typical calibrated reflectivities: painted walls, darker floors, bright ceilings.
    double reflectivity = 55.0;
    if (polygon.kind == maps::SurfaceKind::Floor) reflectivity = 35.0;
    if (polygon.kind == maps::SurfaceKind::Ceiling) reflectivity = 70.0;
    materials.push_back({reflectivity, SurfaceOrigin::Map});
  }
  // Keep clutter off the path: floor points every 0.2 s, raised to the sensor.
  std::vector<Eigen::Vector3d> path;
  const double end = trajectory.duration_s();
  for (double t = 0.0; t <= end + 0.2; t += 0.2) path.push_back(trajectory.floor_point(t));
  Clutter clutter = make_clutter(map, path, config.clutter, streams.clutter);
  boxes = clutter.boxes;
  for (auto& polygon : clutter.polygons) polygons.push_back(std::move(polygon));
  for (const auto& material : clutter.materials) materials.push_back(material);
  return World(std::move(polygons), std::move(materials), std::move(clutter.people));
}

// The packet an encoder completed from a packet's worth of sequences.
io::EncodedPacket only_packet(io::PacketEncoder& encoder) {
  std::vector<io::EncodedPacket> packets = encoder.take_packets();
  if (packets.size() != 1) throw std::logic_error("a packet's sequences made no single packet");
  return std::move(packets.front());
}

}  // namespace

void SimulationConfig::disable_effects() {
  effects.range_noise_m = 0.0;
  effects.quantisation_m = 0.0;
  effects.dropout_rate = 0.0;
  effects.elevation_error_deg = 0.0;
  effects.offset_error_m = 0.0;
  effects.azimuth_error_deg = 0.0;
  map_error_m = 0.0;
  clutter.level = 0;
}

Simulation::Simulation(const maps::PlaneMap& map, SimulationConfig config)
    : config_(std::move(config)), trajectory_({}, config_.trajectory, odometry_rng_) {
  if (config_.sensor.rpm < 300.0 || config_.sensor.rpm > 1200.0) {
    throw std::invalid_argument("rpm must be within 300..1200");
  }
  Streams streams(config_.seed);
  const maps::PlaneMap navigable = with_navigation_geometry(map);
  trajectory_ = plan_trajectory(navigable, config_, streams);
  world_ = build_world(navigable, config_, trajectory_, streams, furniture_boxes_);
  simulator_ =
      std::make_unique<Vlp16Simulator>(world_, sensor::builtin_calibration(config_.model),
                                       config_.sensor, config_.effects, streams.calibration);
  if (config_.second_sensor) {
    second_simulator_ = std::make_unique<Vlp16Simulator>(
        world_, sensor::builtin_calibration(config_.model), config_.sensor, config_.effects,
        streams.second_calibration);
  }
  odometry_rng_ = streams.odometry;
  // Put through the generator, so that noise seed N draws apart from the stream seed N gives.
  packet_seed_ = config_.noise_seed ? std::mt19937_64(*config_.noise_seed)() : streams.packets;
  duration_s_ = config_.duration_s > 0.0 ? config_.duration_s : trajectory_.duration_s();
}

double Simulation::device_time_offset_s() const {
  return std::fmod(config_.start_epoch_s, 3600.0);
}

SimulationStats Simulation::run(const PacketSink& sink, const PacketSink& second_sink) {
  io::EncoderConfig encoder_config;
  encoder_config.model = config_.model;
  encoder_config.return_mode = config_.sensor.dual_return ? io::velodyne::ReturnMode::Dual
                                                          : io::velodyne::ReturnMode::Strongest;
  const bool two = second_simulator_ != nullptr;
  const int per_packet = io::PacketEncoder(encoder_config).sequences_per_packet();
  const double offset_s = device_time_offset_s();
  const double hour_base_s = config_.start_epoch_s - offset_s;
  const auto packets =
      static_cast<std::uint64_t>(std::ceil(duration_s_ / (per_packet * kSequencePeriod_s) - 1e-9));
  SimulationStats stats;
  stats.furniture_boxes = furniture_boxes_;
  stats.people = static_cast<int>(world_.people().size());
  stats.path_length_m = trajectory_.length_m();
  packet_times_s_.clear();

  // The two sensors fire on one schedule, so each of the first sensor's packets is followed by
  // the second's of the same time.
  auto emit = [&](const io::EncodedPacket& packet, int sensor) {
    if (sensor == 0) {
      packet_times_s_.push_back(packet.time_s - offset_s);
      sink(packet, hour_base_s + packet.time_s);
    } else if (second_sink) {
      second_sink(packet, hour_base_s + packet.time_s);
    }
    ++stats.packets;
  };

  // Packets are fired and encoded in chunks; within one, the workers take runs of consecutive
  // packets as they come free (a run's cost follows what the sensor sees). Each packet has its
  // own random stream (seeded from the seed, the packet number and, for the second sensor, its
  // index) and is encoded alone (every packet is whole, so an encoder holds nothing across
  // packets): the bytes do not depend on the threads.
  const int threads = std::max(1, config_.threads);
  constexpr std::uint64_t kChunk = 256;
  constexpr std::size_t kRun = 4;
  std::vector<io::EncodedPacket> encoded, second_encoded;
  std::vector<SensorStats> thread_stats(threads);
  for (std::uint64_t first = 0; first < packets; first += kChunk) {
    const std::uint64_t count = std::min(kChunk, packets - first);
    encoded.assign(count, io::EncodedPacket{});
    if (two) second_encoded.assign(count, io::EncodedPacket{});
    const auto work = [&](std::size_t begin, std::size_t end, int worker) {
      // Each laser's last hit, tried first by its next ray (speed only: PolygonHit's ties make
      // the hits the same whatever is tried first), from the run's first packet on.
      std::array<int, 16> hints, second_hints;
      hints.fill(-1);
      second_hints.fill(-1);
      io::PacketEncoder packet_encoder(encoder_config);
      io::PacketEncoder second_packet_encoder(encoder_config);
      for (std::uint64_t p = first + begin; p < first + end; ++p) {
        std::seed_seq seq{packet_seed_, static_cast<std::uint64_t>(p)};
        std::mt19937_64 rng(seq);
        // The second sensor's generator only where there is one: seeding costs ~10 µs a packet.
        std::optional<std::mt19937_64> second_rng;
        if (two) {
          std::seed_seq second_seq{packet_seed_, static_cast<std::uint64_t>(p), std::uint64_t{1}};
          second_rng.emplace(second_seq);
        }
        for (int s = 0; s < per_packet; ++s) {
          const double t = static_cast<double>(p * per_packet + s) * kSequencePeriod_s;
          const Eigen::Isometry3d T_map_sensor = trajectory_.T_map_sensor(t);
          packet_encoder.add(
              simulator_->fire(t, offset_s, T_map_sensor, rng, hints, thread_stats[worker]));
          if (two) {
            second_packet_encoder.add(
                second_simulator_->fire(t, offset_s, T_map_sensor * *config_.second_sensor,
                                        *second_rng, second_hints, thread_stats[worker]));
          }
        }
        encoded[p - first] = only_packet(packet_encoder);
        if (two) second_encoded[p - first] = only_packet(second_packet_encoder);
      }
    };
    parallel_for_runs(count, kRun, threads, work);
    for (std::size_t i = 0; i < count; ++i) {
      emit(encoded[i], 0);
      if (two) emit(second_encoded[i], 1);
    }
    stats.sequences += count * per_packet * (two ? 2 : 1);
  }
  for (const auto& s : thread_stats) stats.sensor += s;
  return stats;
}

std::vector<io::StampedPose> Simulation::truth() const {
  std::vector<io::StampedPose> poses;
  auto add = [&](double t) {
    poses.push_back(io::StampedPose{config_.start_epoch_s + t, trajectory_.T_map_sensor(t)});
  };
  if (config_.truth_per_packet && !packet_times_s_.empty()) {
    for (const double t : packet_times_s_) add(t);
    return poses;
  }
  const double scan_period_s = 60.0 / config_.sensor.rpm;
  for (std::uint64_t k = 0; k * scan_period_s < duration_s_; ++k) add(k * scan_period_s);
  add(duration_s_);
  return poses;
}

std::vector<io::StampedPose> Simulation::odometry() const {
  std::mt19937_64 rng = odometry_rng_;
  return simulate_odometry(trajectory_, duration_s_, config_.start_epoch_s, config_.odometry, rng);
}

}  // namespace conicloc::sim
