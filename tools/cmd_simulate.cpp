// `conicloc simulate --out run.pcap --truth truth.tum`: a VLP-16 recording with known truth.
#include <arpa/inet.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <fstream>
#include <thread>

#include "io/indoorgml.hpp"
#include "io/input_error.hpp"
#include "io/pcap_writer.hpp"
#include "io/tum_trajectory.hpp"
#include "io/udp_endpoint.hpp"
#include "io/velodyne_packet.hpp"
#include "io/veloview_calibration.hpp"
#include "localizer/conic/pose.hpp"
#include "sensor/builtin_calibration.hpp"
#include "sim/map_fit.hpp"
#include "sim/simulation.hpp"
#include "sim/waypoint_file.hpp"
#include "tools/commands.hpp"
#include "tools/json_writer.hpp"
#include "tools/map_options.hpp"
#include "tools/number_list.hpp"

namespace conicloc::tools {
namespace {

struct SimulateOptions {
  std::string map_path;
  std::string out_path;
  std::string truth_path;
  std::string odom_path;
  std::string map_fit_path;
  std::string calib_truth_path;
  std::string calib_truth_xml_path;
  std::string second_calib_truth_xml_path;
  double calib_offset_error_mm = 0.0;
  std::string waypoints_path;
  std::string motion = "robot";
  std::string start_node;
  bool no_effects = false;
  std::string second_sensor_text;  ///< "x,y,z,roll_deg,pitch_deg,yaw_deg" in the first's frame
  std::string second_sensor_endpoint = "192.168.1.202:2369";  ///< its address and data port
  io::MapLoadOptions map_options;
  sim::SimulationConfig config;
};

// A waypoint outside the building gives a recording of empty space (or, far away, a path whose
// length overflows): refuse it, naming the waypoint.
void check_waypoints_in_map(const std::string& path, const std::vector<sim::Waypoint>& waypoints,
                            const maps::PlaneMap& map) {
  constexpr double kMargin_m = 1.0;
  Eigen::AlignedBox3d allowed = map.bounds;
  allowed.min().array() -= kMargin_m;
  allowed.max().array() += kMargin_m;
  for (std::size_t i = 0; i < waypoints.size(); ++i) {
    const Eigen::Vector3d& p = waypoints[i].floor_point;
    if (allowed.contains(p)) continue;
    throw io::InputError(
        path, "waypoint " + std::to_string(i + 1),
        fmt::format("({:.3g}, {:.3g}, {:.3g}) m is outside the building (map frame "
                    "{:.2f}..{:.2f}, {:.2f}..{:.2f}, {:.2f}..{:.2f} m)",
                    p.x(), p.y(), p.z(), map.bounds.min().x(), map.bounds.max().x(),
                    map.bounds.min().y(), map.bounds.max().y(), map.bounds.min().z(),
                    map.bounds.max().z()));
  }
}

// A simulated sensor's true per-laser calibration and its errors from the nominal table.
void write_true_lasers(JsonWriter& j, const sim::Vlp16Simulator& sensor) {
  constexpr double kDeg = 180.0 / M_PI;
  const auto& nominal = sensor.nominal_calibration().lasers;
  const auto& truth = sensor.true_calibration().lasers;
  j.key("lasers").begin_array();
  for (std::size_t k = 0; k < truth.size(); ++k) {
    j.begin_object();
    j.key("laser_id").value(static_cast<int>(k));
    j.key("ring").value(truth[k].ring);
    j.key("elevation_deg").value(truth[k].elevation_rad * kDeg);
    j.key("vertical_offset_m").value(truth[k].vertical_offset_m);
    j.key("azimuth_offset_deg").value(truth[k].azimuth_offset_rad * kDeg);
    j.key("range_offset_m").value(truth[k].range_offset_m);
    j.key("elevation_error_deg").value((truth[k].elevation_rad - nominal[k].elevation_rad) * kDeg);
    j.key("vertical_offset_error_m")
        .value(truth[k].vertical_offset_m - nominal[k].vertical_offset_m);
    j.key("azimuth_offset_error_deg")
        .value((truth[k].azimuth_offset_rad - nominal[k].azimuth_offset_rad) * kDeg);
    j.key("range_offset_error_m").value(truth[k].range_offset_m - nominal[k].range_offset_m);
    j.end_object();
  }
  j.end_array();
}

// The second sensor's pose in the first's frame (what `calibrate --second-sensor` estimates) and
// where its packets go, with its own lasers' truth when `lasers` is given; nothing without one.
void write_second_sensor(JsonWriter& j, const SimulateOptions& o,
                         const sim::Vlp16Simulator* lasers = nullptr) {
  const auto& second = o.config.second_sensor;
  if (!second) return;
  constexpr double kDeg = 180.0 / M_PI;
  const auto angles = localizer::roll_pitch_yaw(second->linear());
  const Eigen::Vector3d t = second->translation();
  j.key("second_sensor").begin_object();
  j.key("sensor").value(o.second_sensor_endpoint);
  j.key("x_m").value(t.x()).key("y_m").value(t.y()).key("z_m").value(t.z());
  j.key("roll_deg").value(angles.roll * kDeg);
  j.key("pitch_deg").value(angles.pitch * kDeg);
  j.key("yaw_deg").value(angles.yaw * kDeg);
  if (lasers) write_true_lasers(j, *lasers);
  j.end_object();
}

// Every setting and the seed, so a recording can be made again; no wall-clock values.
void write_sidecar(const std::string& path, const SimulateOptions& o,
                   const sim::Simulation& simulation, const sim::SimulationStats& stats) {
  const auto& c = simulation.config();
  std::ofstream out(path);
  JsonWriter j(out);
  j.begin_object();
  j.key("tool").value("conicloc simulate");
  j.key("seed").value(static_cast<unsigned long>(c.seed));
  if (c.noise_seed) j.key("noise_seed").value(static_cast<unsigned long>(*c.noise_seed));
  j.key("map").value(o.map_path);
  j.key("unit_scale").value(o.map_options.unit_scale);
  j.key("storey_height_m").value(o.map_options.storey_height_m);
  j.key("close_doors").value(o.map_options.close_doors);
  j.key("waypoints").value(o.waypoints_path);
  j.key("pcap").value(o.out_path);
  j.key("truth").value(o.truth_path);
  j.key("odometry").value(o.odom_path);
  j.key("map_fit").value(o.map_fit_path);
  j.key("duration_s").value(simulation.duration_s());
  j.key("start_epoch_s").value(c.start_epoch_s);
  j.key("truth_per_packet").value(c.truth_per_packet);
  j.key("truth_time")
      .value(c.truth_per_packet ? "first firing of each packet, UTC"
                                : "start of each rotation, UTC");
  j.key("trajectory").begin_object();
  j.key("motion").value(o.motion);
  j.key("speed_mps").value(c.trajectory.speed_mps);
  j.key("acceleration_mps2").value(c.trajectory.acceleration_mps2);
  j.key("lateral_acceleration_mps2").value(c.trajectory.lateral_acceleration_mps2);
  j.key("yaw_rate_max_radps").value(c.trajectory.yaw_rate_max_radps);
  j.key("yaw_acceleration_max_radps2").value(c.trajectory.yaw_acceleration_max_radps2);
  j.key("sensor_height_m").value(c.trajectory.sensor_height_m);
  j.key("start_node").value(c.route.start_node);
  j.key("door_approach_m").value(c.route.door_approach_m);
  j.key("path_length_m").value(stats.path_length_m);
  j.end_object();
  j.key("sensor").begin_object();
  j.key("model").value("vlp16");
  j.key("rpm").value(c.sensor.rpm);
  j.key("return_mode").value(c.sensor.dual_return ? "dual" : "strongest");
  j.key("beam_divergence_rad").value(c.sensor.beam_divergence_rad);
  j.key("elevation_errors_deg").begin_array();
  for (const double e : simulation.sensor().elevation_errors_rad()) j.value(e * 180.0 / M_PI);
  j.end_array();
  j.end_object();
  write_second_sensor(j, o);
  j.key("effects").begin_object();
  j.key("range_noise_m").value(c.effects.range_noise_m);
  j.key("quantisation_m").value(c.effects.quantisation_m);
  j.key("dropout_rate").value(c.effects.dropout_rate);
  j.key("elevation_error_deg").value(c.effects.elevation_error_deg);
  j.key("calib_offset_error_mm").value(c.effects.offset_error_m * 1000.0);
  j.key("calib_azimuth_error_deg").value(c.effects.azimuth_error_deg);
  j.key("max_range_m").value(c.effects.max_range_m);
  j.key("min_range_m").value(c.effects.min_range_m);
  j.key("map_error_m").value(c.map_error_m);
  j.key("clutter_level").value(c.clutter.level);
  j.key("clutter_clearance_m").value(c.clutter.clearance_m);
  j.end_object();
  j.key("odometry_model").begin_object();
  j.key("rate_hz").value(c.odometry.rate_hz);
  j.key("speed_scale_sigma").value(c.odometry.speed_scale_sigma);
  j.key("speed_noise_mps").value(c.odometry.speed_noise_mps);
  j.key("yaw_rate_bias_radps").value(c.odometry.yaw_rate_bias_radps);
  j.key("yaw_rate_bias_walk").value(c.odometry.yaw_rate_bias_walk);
  j.key("yaw_rate_noise_radps").value(c.odometry.yaw_rate_noise_radps);
  j.end_object();
  const auto& s = stats.sensor;
  j.key("stats").begin_object();
  j.key("packets").value(static_cast<unsigned long>(stats.packets));
  j.key("rays").value(static_cast<unsigned long>(s.rays));
  j.key("map_hits").value(static_cast<unsigned long>(s.map_hits));
  j.key("furniture_hits").value(static_cast<unsigned long>(s.furniture_hits));
  j.key("person_hits").value(static_cast<unsigned long>(s.person_hits));
  j.key("dropouts").value(static_cast<unsigned long>(s.dropouts));
  j.key("no_surface").value(static_cast<unsigned long>(s.no_surface));
  j.key("blind_zone").value(static_cast<unsigned long>(s.blind_zone));
  j.key("second_echoes").value(static_cast<unsigned long>(s.second_echoes));
  j.key("furniture_boxes").value(stats.furniture_boxes);
  j.key("people").value(stats.people);
  j.end_object();
  j.end_object();
  out << '\n';
  if (!out) throw io::InputError(path, "", "cannot write the JSON sidecar");
}

// What the simulated sensor really is, per laser, next to its nominal table: the answer that
// `conicloc calibrate --truth` scores its estimates against.
void write_calibration_truth(const std::string& path, const SimulateOptions& o,
                             const sim::Simulation& simulation) {
  const auto& c = simulation.config();
  std::ofstream out(path);
  JsonWriter j(out);
  j.begin_object();
  j.key("tool").value("conicloc simulate");
  j.key("seed").value(static_cast<unsigned long>(c.seed));
  j.key("pcap").value(o.out_path);
  j.key("calib_error_deg").value(c.effects.elevation_error_deg);
  j.key("elevation_error").value("uniform in ±calib_error_deg");
  j.key("calib_offset_error_mm").value(c.effects.offset_error_m * 1000.0);
  j.key("calib_azimuth_error_deg").value(c.effects.azimuth_error_deg);
  j.key("offset_error").value("Gaussian, sigma calib_offset_error_mm / calib_azimuth_error_deg");
  j.key("mounting").begin_object();
  j.key("height_m").value(simulation.trajectory().config().sensor_height_m);
  j.key("roll_deg").value(simulation.trajectory().config().mount_roll_deg);
  j.key("pitch_deg").value(simulation.trajectory().config().mount_pitch_deg);
  j.end_object();
  write_second_sensor(j, o, simulation.second_sensor());
  write_true_lasers(j, simulation.sensor());
  j.end_object();
  out << '\n';
  if (!out) throw io::InputError(path, "", "cannot write the calibration truth");
}

void run_simulate(SimulateOptions& o) {
  auto& config = o.config;
  if (o.motion == "robot") {
    config.trajectory.style = sim::MotionStyle::Robot;
  } else if (o.motion == "handheld") {
    config.trajectory.style = sim::MotionStyle::Handheld;
  } else {
    throw CLI::ValidationError("--motion", "expected robot or handheld, got " + o.motion);
  }
  config.effects.offset_error_m = o.calib_offset_error_mm * 1e-3;
  if (o.no_effects) config.disable_effects();
  config.route.start_node = o.start_node;
  if (o.map_path.empty()) o.map_path = example_map_path();
  const maps::PlaneMap map = load_map(o.map_path, o.map_options).map;
  if (!o.waypoints_path.empty()) {
    config.waypoints = sim::read_waypoints(o.waypoints_path);
    check_waypoints_in_map(o.waypoints_path, config.waypoints, map);
  }

  io::UdpEndpoints second_endpoints;
  if (!o.second_sensor_text.empty()) {
    const auto v = parse_numbers(o.second_sensor_text, 6, "--second-sensor");
    config.second_sensor = localizer::make_pose(v[0], v[1], v[2], v[5] * M_PI / 180.0,
                                                v[4] * M_PI / 180.0, v[3] * M_PI / 180.0);
    const io::UdpEndpoint endpoint =
        io::parse_send_endpoint(o.second_sensor_endpoint, "--second-sensor-address");
    const std::uint32_t address = ntohl(io::socket_address(endpoint).sin_addr.s_addr);
    second_endpoints.src_ip = {static_cast<std::uint8_t>(address >> 24),
                               static_cast<std::uint8_t>(address >> 16),
                               static_cast<std::uint8_t>(address >> 8),
                               static_cast<std::uint8_t>(address)};
    second_endpoints.src_mac[5] = 0x02;
    second_endpoints.src_port = endpoint.port;
    second_endpoints.dst_port = endpoint.port;
  }
  sim::Simulation simulation(map, config);
  spdlog::info("trajectory: {:.1f} m in {:.1f} s; simulating {:.1f} s",
               simulation.trajectory().length_m(), simulation.trajectory().duration_s(),
               simulation.duration_s());
  if (simulation.trajectory().duration_s() < simulation.duration_s() - 1e-6) {
    // A route the graph cuts short (a start cell without a way out) leaves the sensor standing.
    spdlog::warn("the route ends after {:.1f} s: the sensor stands still for the last {:.1f} s",
                 simulation.trajectory().duration_s(),
                 simulation.duration_s() - simulation.trajectory().duration_s());
  }
  io::PcapWriter pcap(o.out_path);
  const auto wall_start = std::chrono::steady_clock::now();
  const auto stats = simulation.run(
      [&](const io::EncodedPacket& packet, double utc_time_s) {
        pcap.write_udp(packet.payload, utc_time_s);
      },
      [&](const io::EncodedPacket& packet, double utc_time_s) {
        pcap.write_udp(packet.payload, utc_time_s, second_endpoints);
      });
  pcap.close();
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  io::write_tum(o.truth_path, simulation.truth());
  if (!o.odom_path.empty()) io::write_tum(o.odom_path, simulation.odometry());
  if (!o.map_fit_path.empty()) {
    const auto fit_start = std::chrono::steady_clock::now();
    const std::vector<io::StampedPose> truth = simulation.truth();
    sim::MapFitConfig fit;
    fit.threads = config.threads;
    io::write_tum(o.map_fit_path,
                  sim::map_fit_poses(map, simulation.world(),
                                     sensor::builtin_calibration(config.model), truth, fit));
    spdlog::info("map fit of {} truth poses in {:.2f} s: {}", truth.size(),
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - fit_start).count(),
                 o.map_fit_path);
  }
  write_sidecar(o.out_path + ".json", o, simulation, stats);
  if (!o.calib_truth_path.empty()) write_calibration_truth(o.calib_truth_path, o, simulation);
  const double distance_unit_m =
      io::velodyne::packet_layout(simulation.config().model).distance_unit_m;
  if (!o.calib_truth_xml_path.empty()) {
    io::write_veloview_calibration(o.calib_truth_xml_path, simulation.sensor().true_calibration(),
                                   distance_unit_m);
  }
  if (!o.second_calib_truth_xml_path.empty()) {
    io::write_veloview_calibration(o.second_calib_truth_xml_path,
                                   simulation.second_sensor()->true_calibration(), distance_unit_m);
  }
  const auto& s = stats.sensor;
  spdlog::info(
      "{} packets, {} rays: {} map, {} furniture, {} people, {} dropped, {} no surface, {} blocked "
      "in the blind zone",
      stats.packets, s.rays, s.map_hits, s.furniture_hits, s.person_hits, s.dropouts, s.no_surface,
      s.blind_zone);
  spdlog::info("{:.1f}x real time ({:.2f} s wall)",
               simulation.duration_s() / std::max(wall_s, 1e-9), wall_s);
}

}  // namespace

void add_simulate_command(CLI::App& app) {
  auto o = std::make_shared<SimulateOptions>();
  auto& c = o->config;
  c.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  auto* cmd = app.add_subcommand("simulate", "Simulate a VLP-16 recording (pcap, truth, odometry)");
  cmd->add_option("--map", o->map_path, "IndoorGML building (default: the example building)")
      ->check(CLI::ExistingFile);
  add_map_load_options(cmd, o->map_options);
  cmd->add_option("--out", o->out_path, "pcap to write (plus OUT.json with the settings)")
      ->required();
  cmd->add_option("--truth", o->truth_path, "Ground-truth sensor poses (TUM)")->required();
  cmd->add_option("--odom", o->odom_path, "Drifting wheel/IMU odometry (TUM)");
  cmd->add_option("--map-fit", o->map_fit_path,
                  "The pose the map gives each truth pose (TUM): where the map's planes best fit, "
                  "in least squares, what the sensor there sees of the real walls (moved by "
                  "--map-error): how far the map's error alone pulls a localizer that trusts it");
  cmd->add_option("--duration", c.duration_s, "Seconds to simulate (<=0: the whole path)")
      ->capture_default_str();
  cmd->add_option("--waypoints", o->waypoints_path, "Waypoint file: 'x y [z] [yaw_deg]' per line")
      ->check(CLI::ExistingFile);
  cmd->add_option("--start-node", o->start_node, "Navigation node id to start at");
  cmd->add_option("--seed", c.seed, "Seed of every random choice")->capture_default_str();
  cmd->add_option("--noise-seed", c.noise_seed,
                  "Seed of the per-return draws alone (range noise, intensity, dropouts): the "
                  "same route, world and calibration errors as --seed's with new noise, for a "
                  "Monte Carlo of what the noise alone moves");
  cmd->add_option("--noise", c.effects.range_noise_m, "Range noise sigma, m")
      ->capture_default_str();
  cmd->add_option("--quantisation", c.effects.quantisation_m, "Range resolution, m")
      ->capture_default_str();
  cmd->add_option("--dropout", c.effects.dropout_rate, "Fraction of returns lost")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--clutter", c.clutter.level, "Furniture and people: 0 none .. 3 heavy")
      ->check(CLI::Range(0, 3))
      ->capture_default_str();
  cmd->add_option("--map-error", c.map_error_m, "Sigma of wall shifts and tilts, m")
      ->capture_default_str();
  cmd->add_option("--calib-error-deg", c.effects.elevation_error_deg,
                  "Per-laser elevation error bound, degrees")
      ->capture_default_str();
  cmd->add_option("--calib-offset-error-mm", o->calib_offset_error_mm,
                  "Sigma of per-laser vertical and range offset errors, mm")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--calib-azimuth-error-deg", c.effects.azimuth_error_deg,
                  "Sigma of per-laser azimuth offset errors, degrees")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--calib-truth", o->calib_truth_path,
                  "Write the true per-laser calibration and its errors (JSON)");
  cmd->add_option("--calib-truth-xml", o->calib_truth_xml_path,
                  "Write the true calibration as VeloView XML (for calibrate --truth)");
  cmd->add_option("--max-range", c.effects.max_range_m, "Maximum range, m")->capture_default_str();
  cmd->add_flag("--no-effects", o->no_effects, "Exact ranges and the map as the world");
  cmd->add_option("--rpm", c.sensor.rpm, "Rotation speed")
      ->check(CLI::Range(300.0, 1200.0))
      ->capture_default_str();
  cmd->add_flag("--dual", c.sensor.dual_return, "Dual return mode (last + strongest)");
  cmd->add_option("--motion", o->motion, "robot or handheld")->capture_default_str();
  cmd->add_option("--speed", c.trajectory.speed_mps, "Cruise speed, m/s")->capture_default_str();
  cmd->add_option("--yaw-acceleration", c.trajectory.yaw_acceleration_max_radps2,
                  "How fast the carrier's yaw rate may change, rad/s^2")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--sensor-height", c.trajectory.sensor_height_m,
                  "Sensor above the floor, m (<0: 0.8 robot, 1.4 handheld)")
      ->capture_default_str();
  cmd->add_option("--mount-roll-deg", c.trajectory.mount_roll_deg,
                  "Fixed roll of the sensor on its carrier, degrees")
      ->capture_default_str();
  cmd->add_option("--mount-pitch-deg", c.trajectory.mount_pitch_deg,
                  "Fixed pitch of the sensor on its carrier, degrees")
      ->capture_default_str();
  auto* second = cmd->add_option(
      "--second-sensor", o->second_sensor_text,
      "A second sensor on the carrier, x,y,z,roll_deg,pitch_deg,yaw_deg in the first sensor's "
      "frame: its packets go into the same capture");
  cmd->add_option("--second-sensor-address", o->second_sensor_endpoint,
                  "The second sensor's ADDR:PORT (sender address and data port)")
      ->capture_default_str()
      ->needs(second);
  cmd->add_option("--second-calib-truth-xml", o->second_calib_truth_xml_path,
                  "Write the second sensor's true calibration as VeloView XML (for calibrate "
                  "--sensor ADDR:PORT --truth)")
      ->needs(second);
  cmd->add_option("--start-epoch", c.start_epoch_s,
                  "UTC seconds of the first firing (device clock: us past the hour)")
      ->capture_default_str();
  cmd->add_flag("--truth-per-packet", c.truth_per_packet,
                "One truth pose per packet, not per scan");
  cmd->add_option("--odom-rate", c.odometry.rate_hz, "Odometry rate, Hz")->capture_default_str();
  cmd->add_option("--threads", c.threads, "Ray casting threads (output is the same)")
      ->capture_default_str();
  cmd->callback([o] { run_simulate(*o); });
}

}  // namespace conicloc::tools
