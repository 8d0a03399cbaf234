// `conicloc localize --map building.gml --pcap run.pcap --out poses.tum`: a pose per scan.
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>

#include "io/indoorgml.hpp"
#include "io/input_error.hpp"
#include "io/pcap_reader.hpp"
#include "io/scan_assembler.hpp"
#include "io/tum_trajectory.hpp"
#include "io/velodyne_stream.hpp"
#include "localizer/localizer.hpp"
#include "localizer/parallel_for.hpp"
#include "localizer/relative_motion.hpp"
#include "sensor/builtin_calibration.hpp"
#include "tools/commands.hpp"

namespace conicloc::tools {
namespace {

struct LocalizeOptions {
  std::string map_path;
  std::string pcap_path;
  std::string out_path;
  std::string details_path;
  std::string odom_path;
  std::string init_text;                      ///< "x,y,z,yaw_deg"
  std::string init_sigma_text = "0.2,0.2,5";  ///< "sigma_xy_m,sigma_xy_m,sigma_yaw_deg"
  std::string sensor_model = "vlp16";
  bool global = false;
  double height_m = 0.8;  ///< mounting height above the floor for --global
  int skip_partial = 1;
  localizer::LocalizerConfig config;
};

std::vector<double> parse_numbers(const std::string& text, std::size_t count,
                                  const std::string& flag) {
  std::vector<double> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    try {
      std::size_t used = 0;
      values.push_back(std::stod(item, &used));
      if (used != item.size() || !std::isfinite(values.back())) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw CLI::ValidationError(flag, "'" + item + "' is not a number");
    }
  }
  if (values.size() != count) {
    throw CLI::ValidationError(
        flag, "expected " + std::to_string(count) + " comma-separated numbers, got '" + text + "'");
  }
  return values;
}

// Passes datagrams through and remembers the capture time of the last one, so device times can
// be related to the capture's UTC clock (truth and odometry files are stamped in UTC).
class TimedSource final : public io::DatagramSource {
 public:
  explicit TimedSource(io::DatagramSource& inner) : inner_(inner) {}
  std::optional<io::UdpDatagram> next() override {
    auto datagram = inner_.next();
    if (datagram) last_capture_time_s = datagram->capture_time_s;
    return datagram;
  }
  std::string name() const override { return inner_.name(); }
  double last_capture_time_s = 0.0;

 private:
  io::DatagramSource& inner_;
};

// Odometry pose at `time_s`, interpolated; nullopt outside the file's time span.
std::optional<localizer::Pose3> odometry_at(const std::vector<io::StampedPose>& odometry,
                                            double time_s) {
  if (odometry.empty() || time_s < odometry.front().time_s || time_s > odometry.back().time_s)
    return std::nullopt;
  const auto after =
      std::lower_bound(odometry.begin(), odometry.end(), time_s,
                       [](const io::StampedPose& p, double t) { return p.time_s < t; });
  if (after == odometry.begin()) return after->pose;
  const auto before = after - 1;
  const double span = after->time_s - before->time_s;
  return localizer::interpolate_pose(before->pose, after->pose,
                                     span > 0 ? (time_s - before->time_s) / span : 0.0);
}

class Progress {
 public:
  Progress() : enabled_(isatty(STDERR_FILENO) == 1) {}
  void update(std::size_t scans, double capture_s, const localizer::UpdateResult& r) {
    if (!enabled_ || scans % 5 != 0) return;
    std::fprintf(stderr, "\r  scan %6zu  %7.1f s  x %8.2f  y %8.2f  %6.1f ms  %5zu particles ",
                 scans, capture_s, r.pose.translation().x(), r.pose.translation().y(),
                 r.run_time_ms, r.particles);
    std::fflush(stderr);
  }
  void finish() {
    if (enabled_) std::fprintf(stderr, "\n");
  }

 private:
  bool enabled_;
};

void run_localize(const LocalizeOptions& o) {
  const auto model = sensor::parse_sensor_model(o.sensor_model);
  if (!model)
    throw CLI::ValidationError("--sensor-model", "unknown sensor model '" + o.sensor_model + "'");
  const sensor::LaserCalibration calibration = sensor::builtin_calibration(*model);

  auto loaded = io::load_indoorgml(o.map_path);
  for (const auto& warning : loaded.report.warnings) spdlog::warn("{}: {}", o.map_path, warning);
  const maps::PlaneMap& map = loaded.map;
  spdlog::info("map {}: {} polygons, {} cells", o.map_path, map.polygons.size(), map.cells.size());

  localizer::LocalizerConfig config = o.config;
  if (loaded.report.two_sided_faces > 0) {
    // One polygon serves both sides of a wall: a wall seen from behind is still a wall.
    config.observation.conic_beam.cull.cull_back_faces = false;
    config.observation.conic_segment.cull.cull_back_faces = false;
  }
  config.motion.height_above_floor_m = o.height_m;
  localizer::Localizer localizer(map, calibration, config);
  if (!o.init_text.empty() && !o.global) {
    const auto init = parse_numbers(o.init_text, 4, "--init");
    const auto sigma = parse_numbers(o.init_sigma_text, 3, "--init-sigma");
    localizer::Vector6 sigma6;
    sigma6 << sigma[0], sigma[1], 0.02, 0.01, 0.01, sigma[2] * M_PI / 180.0;
    localizer.initialise(localizer::make_pose(init[0], init[1], init[2], init[3] * M_PI / 180.0),
                         sigma6);
  } else {
    localizer.initialise_global();
    if (localizer.particles().empty()) {
      throw std::runtime_error(o.map_path + ": no navigable cell with a floor area for --global");
    }
  }
  spdlog::info("model {}, {} particles, {} threads, seed {}", config.observation.model,
               localizer.particles().size(), localizer::resolve_thread_count(config.threads),
               config.seed);

  std::vector<io::StampedPose> odometry;
  if (!o.odom_path.empty()) odometry = io::read_tum(o.odom_path);

  std::ofstream out(o.out_path);
  if (!out) throw io::InputError(o.out_path, "", "cannot open for writing");
  std::ofstream details;
  if (!o.details_path.empty()) {
    details.open(o.details_path);
    if (!details) throw io::InputError(o.details_path, "", "cannot open for writing");
    details
        << "time_s,x,y,z,qx,qy,qz,qw,var_x,var_y,var_z,var_roll,var_pitch,var_yaw,ess,particles,"
           "log_likelihood,inlier_fraction,terms,time_ms,recovered\n";
  }

  io::PcapReader reader(o.pcap_path, {2368, 8308});
  TimedSource source(reader);
  io::VelodyneStream stream(source, calibration);
  io::ScanAssembler assembler(calibration);
  std::optional<double> utc_offset_s;  // UTC − device time
  std::optional<localizer::Pose3> last_odometry;
  std::size_t scans = 0, recoveries = 0, skipped = 0;
  double total_ms = 0.0, max_ms = 0.0, first_time = 0.0, last_time = 0.0;
  Progress progress;

  const auto process = [&](const sensor::Scan& scan) {
    if (scan.partial && o.skip_partial && scan.valid_returns() == 0) {
      ++skipped;
      return;
    }
    const double utc_s = scan.end_time_s + utc_offset_s.value_or(0.0);
    std::optional<localizer::Pose3> motion;
    if (!odometry.empty()) {
      const auto now = odometry_at(odometry, utc_s);
      if (now && last_odometry) motion = last_odometry->inverse() * *now;
      last_odometry = now;
    }
    const localizer::UpdateResult r = localizer.update(scan, motion);
    if (scans == 0) first_time = utc_s;
    last_time = utc_s;
    ++scans;
    total_ms += r.run_time_ms;
    max_ms = std::max(max_ms, r.run_time_ms);
    recoveries += r.recovered ? 1 : 0;
    if (r.recovered) spdlog::debug("scan {}: filter lost, global particles injected", scan.index);
    io::write_tum_line(out, {utc_s, r.pose});
    if (details.is_open()) {
      const Eigen::Quaterniond q(r.pose.linear());
      const Eigen::Vector3d t = r.pose.translation();
      details << fmt::format("{:.6f},{:.4f},{:.4f},{:.4f},{:.9f},{:.9f},{:.9f},{:.9f}", utc_s,
                             t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w());
      for (int i = 0; i < 6; ++i) details << fmt::format(",{:.6g}", r.covariance(i, i));
      details << fmt::format(",{:.2f},{},{:.4f},{:.4f},{},{:.3f},{}\n", r.ess, r.particles,
                             r.log_likelihood, r.inlier_fraction, r.terms, r.run_time_ms,
                             r.recovered ? 1 : 0);
    }
    progress.update(scans, utc_s - first_time, r);
  };

  std::vector<io::DecodedPoint> points;
  std::vector<sensor::Scan> completed;
  while (stream.next(points)) {
    if (!utc_offset_s && !points.empty()) {
      // The packet leaves the sensor after its last firing.
      utc_offset_s = source.last_capture_time_s - points.back().time_s;
    }
    assembler.add(points, completed);
    for (const auto& scan : completed) process(scan);
    completed.clear();
  }
  if (auto last = assembler.finish()) process(*last);
  progress.finish();

  for (const auto& warning : stream.warnings()) spdlog::warn("{}: {}", o.pcap_path, warning);
  const auto& stats = stream.stats();
  const double capture_s = scans > 1 ? last_time - first_time : 0.0;
  spdlog::info("{} scans localized ({} empty partial skipped), {} recoveries", scans, skipped,
               recoveries);
  if (scans > 0) {
    const double mean_ms = total_ms / static_cast<double>(scans);
    spdlog::info("time per scan: mean {:.1f} ms, max {:.1f} ms; real-time factor {:.1f}x", mean_ms,
                 max_ms, total_ms > 0 ? capture_s * 1000.0 / total_ms : 0.0);
  }
  spdlog::info("packets: {} decoded, {} rejected, ~{} lost; {} truncated capture records",
               stats.data_packets, stats.rejected_total(), stats.packets_lost,
               reader.counts().truncated_records);
  spdlog::info("poses written to {}", o.out_path);
  if (scans == 0) throw CLI::RuntimeError(2);
}

}  // namespace

void add_localize_command(CLI::App& app) {
  auto options = std::make_shared<LocalizeOptions>();
  options->map_path = example_map_path();
  auto* cmd = app.add_subcommand("localize", "Estimate the sensor pose at every scan of a capture");
  cmd->add_option("--map", options->map_path, "IndoorGML building model")->check(CLI::ExistingFile);
  cmd->add_option("--pcap", options->pcap_path, "pcap/pcapng capture of the sensor")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", options->out_path, "Output trajectory (TUM, UTC time stamps)")
      ->required();
  cmd->add_option("--details", options->details_path, "Per-scan diagnostics (CSV)");
  cmd->add_option("--init", options->init_text, "Initial pose x,y,z,yaw_deg (map frame)");
  cmd->add_option("--init-sigma", options->init_sigma_text,
                  "Initial std. dev. sigma_x,sigma_y,sigma_yaw_deg")
      ->capture_default_str();
  cmd->add_flag("--global", options->global, "Global localization over all navigable cells");
  cmd->add_option("--odom", options->odom_path, "Odometry (TUM, UTC) for the motion model")
      ->check(CLI::ExistingFile);
  cmd->add_option("--model", options->config.observation.model, "Observation model")
      ->check(CLI::IsMember(localizer::observation_model_names()))
      ->capture_default_str();
  cmd->add_option("--particles", options->config.filter.max_particles,
                  "Maximum particles (global start count; KLD adapts below)")
      ->capture_default_str();
  cmd->add_option("--min-particles", options->config.filter.min_particles, "Minimum particles")
      ->capture_default_str();
  cmd->add_option("--init-particles", options->config.filter.initial_particles,
                  "Particles for --init")
      ->capture_default_str();
  cmd->add_option("--threads", options->config.threads, "Worker threads (0: all cores)")
      ->capture_default_str();
  cmd->add_option("--seed", options->config.seed, "Random seed (runs repeat exactly)")
      ->capture_default_str();
  cmd->add_option("--beams", options->config.observation.conic_beam.beams.max_beams,
                  "Beams scored per scan by conic-beam (0: all)")
      ->capture_default_str();
  cmd->add_option("--points", options->config.observation.point_to_plane.beams.max_beams,
                  "Points scored per scan by point-to-plane (0: all)")
      ->capture_default_str();
  cmd->add_option("--tempering", options->config.filter.tempering, "Likelihood exponent")
      ->capture_default_str();
  cmd->add_option("--reference-terms", options->config.filter.reference_terms,
                  "A scan counts as at most this many independent terms (0: no cap)")
      ->capture_default_str();
  cmd->add_option("--height", options->height_m, "Sensor height above the floor for --global (m)")
      ->capture_default_str();
  cmd->add_option("--sensor-model", options->sensor_model,
                  "vlp16, puck-lite, puck-hires, hdl32e, vlp32c")
      ->capture_default_str();
  cmd->add_flag("!--no-deskew", options->config.deskew, "Do not de-skew scans");
  cmd->callback([options] { run_localize(*options); });
}

}  // namespace conicloc::tools
