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
#include "io/tum_trajectory.hpp"
#include "io/veloview_calibration.hpp"
#include "localizer/localizer.hpp"
#include "localizer/parallel_for.hpp"
#include "sensor/builtin_calibration.hpp"
#include "tools/capture_report.hpp"
#include "tools/commands.hpp"
#include "tools/localize_run.hpp"
#include "tools/map_options.hpp"
#include "tools/number_list.hpp"
#include "tools/process_memory.hpp"
#include "tools/status_log.hpp"

namespace conicloc::tools {
namespace {

struct LocalizeOptions {
  std::string map_path;
  std::string pcap_path;
  std::string topic;
  std::string out_path;
  std::string details_path;
  std::string covariance_path;
  std::string odom_path;
  std::string init_text;                      ///< "x,y,z,yaw_deg"
  std::string init_sigma_text = "0.2,0.2,5";  ///< "sigma_xy_m,sigma_xy_m,sigma_yaw_deg"
  std::string sensor_model = "vlp16";
  std::string calibration_xml;
  bool global = false;
  double height_m = 0.8;  ///< mounting height above the floor for --global
  double min_partial_fraction = 0.5;
  io::MapLoadOptions map_options;
  bool trust_units = false;  ///< localize in a map whose sizes look like other units
  localizer::LocalizerConfig config;
};

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

  const auto loaded = load_map(o.map_path, o.map_options);
  if (!o.trust_units) require_plausible_units(o.map_path, loaded, o.map_options);
  const maps::PlaneMap& map = loaded.map;
  spdlog::info("map {}: {} polygons, {} cells", o.map_path, map.polygons.size(), map.cells.size());

  LocalizeRunConfig run;
  run.pcap_path = o.pcap_path;
  run.topic = o.topic;
  run.calibration = sensor::builtin_calibration(*model);
  if (!o.calibration_xml.empty()) {
    auto calibration = io::read_veloview_calibration(o.calibration_xml, *model);
    for (const auto& warning : calibration.warnings) spdlog::warn("{}", warning);
    run.calibration = calibration.calibration;
    spdlog::info("calibration from {}", o.calibration_xml);
  }
  run.localizer = o.config;
  run.localizer.motion.height_above_floor_m = o.height_m;
  run.two_sided_walls = loaded.report.two_sided_faces > 0;
  run.min_partial_fraction = o.min_partial_fraction;
  if (!o.init_text.empty() && !o.global) {
    const auto init = parse_numbers(o.init_text, 4, "--init");
    const auto sigma = parse_numbers(o.init_sigma_text, 3, "--init-sigma");
    run.start.pose = localizer::make_pose(init[0], init[1], init[2], init[3] * M_PI / 180.0);
    run.start.sigma << sigma[0], sigma[1], 0.02, 0.01, 0.01, sigma[2] * M_PI / 180.0;
  } else {
    run.start.global = true;
  }
  if (!o.odom_path.empty()) run.odometry = io::read_tum(o.odom_path);
  spdlog::info("model {}, {} start, {} threads, seed {}", run.localizer.observation.model,
               run.start.global ? "global" : "tracking",
               localizer::resolve_thread_count(run.localizer.threads), run.localizer.seed);

  std::ofstream out(o.out_path);
  if (!out) throw io::InputError(o.out_path, "", "cannot open for writing");
  std::ofstream details;
  if (!o.details_path.empty()) {
    details.open(o.details_path);
    if (!details) throw io::InputError(o.details_path, "", "cannot open for writing");
    details
        << "time_s,x,y,z,qx,qy,qz,qw,var_x,var_y,var_z,var_roll,var_pitch,var_yaw,ess,particles,"
           "log_likelihood,inlier_fraction,terms,time_ms,recovered,peak_rss_mib,tempering,spread_m,"
           "see_through_fraction,status,mode_weight,effective_terms,scan_turn_deg,pose_blur_m\n";
  }
  std::ofstream covariance;
  if (!o.covariance_path.empty()) {
    covariance.open(o.covariance_path);
    if (!covariance) throw io::InputError(o.covariance_path, "", "cannot open for writing");
    covariance << covariance_header() << "\n";
  }
  StatusLog status_log;
  Progress progress;
  std::size_t scans = 0;
  double first_time = 0.0;
  const auto summary =
      run_localization(map, run, [&](double utc_s, const localizer::UpdateResult& r) {
        if (scans++ == 0) first_time = utc_s;
        status_log.update(utc_s - first_time, r);
        io::write_tum_line(out, {utc_s, r.pose});
        if (details.is_open()) {
          const Eigen::Quaterniond q(r.pose.linear());
          const Eigen::Vector3d t = r.pose.translation();
          details << fmt::format("{:.6f},{:.4f},{:.4f},{:.4f},{:.9f},{:.9f},{:.9f},{:.9f}", utc_s,
                                 t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w());
          for (int i = 0; i < 6; ++i) details << fmt::format(",{:.6g}", r.covariance(i, i));
          details << fmt::format(
              ",{:.2f},{},{:.4f},{:.4f},{},{:.3f},{},{:.1f},{:.4g},{:.3f},{:.4f}", r.ess,
              r.particles, r.log_likelihood, r.inlier_fraction, r.terms, r.run_time_ms,
              r.recovered ? 1 : 0, peak_rss_mib(), r.tempering, r.spread_m, r.see_through_fraction);
          details << fmt::format(",{},{:.4f},{:.1f},{:.4f},{:.4f}\n",
                                 localizer::status_name(r.status), r.mode_weight, r.effective_terms,
                                 r.scan_turn_rad * 180.0 / M_PI, r.pose_blur_m);
        }
        if (covariance.is_open()) covariance << covariance_row(utc_s, r.covariance) << "\n";
        progress.update(scans, utc_s - first_time, r);
      });
  progress.finish();
  status_log.finish();

  for (const auto& warning : summary.stream_warnings) spdlog::warn("{}: {}", o.pcap_path, warning);
  log_capture_problems(o.pcap_path, &summary.capture, summary.stream, summary.first_rejections);
  const auto& stats = summary.stream;
  spdlog::info(
      "{} scans localized ({} partial scans empty or under half a rotation skipped), {} "
      "recoveries",
      summary.scans, summary.skipped_partial, summary.recoveries);
  if (summary.scans > 0) {
    spdlog::info(
        "time per scan: mean {:.1f} ms, p95 {:.1f} ms, max {:.1f} ms; real-time factor "
        "{:.1f}x",
        summary.mean_time_ms(), summary.quantile_time_ms(0.95), summary.max_time_ms(),
        summary.realtime_factor());
  }
  if (summary.point_clouds) {
    spdlog::info("point clouds: {} messages read, {} skipped; {} truncated capture records",
                 summary.capture.records, summary.capture.bad_messages,
                 summary.capture.truncated_records);
  } else {
    spdlog::info("packets: {} decoded, {} rejected, ~{} lost; {} truncated capture records",
                 stats.data_packets, stats.rejected_total(), stats.packets_lost,
                 summary.capture.truncated_records);
  }
  spdlog::info("peak memory {:.1f} MiB; poses written to {}", peak_rss_mib(), o.out_path);
  if (summary.scans == 0) throw CLI::RuntimeError(2);
}

}  // namespace

void add_localize_command(CLI::App& app) {
  auto options = std::make_shared<LocalizeOptions>();
  options->map_path = example_map_path();
  auto* cmd = app.add_subcommand("localize", "Estimate the sensor pose at every scan of a capture");
  cmd->add_option("--map", options->map_path, "IndoorGML building model")->check(CLI::ExistingFile);
  add_map_load_options(cmd, options->map_options);
  cmd->add_flag("--trust-units", options->trust_units,
                "Localize even when the map's storey heights or extent look like other units");
  cmd->add_option("--pcap,--capture", options->pcap_path,
                  "Capture of the sensor: pcap/pcapng, or a ROS bag of velodyne_msgs/VelodyneScan "
                  "or sensor_msgs/PointCloud2 (MCAP, ROS 2 .db3 file or folder, ROS 1 .bag), "
                  "recognised by content")
      ->required()
      ->check(CLI::ExistingPath);
  cmd->add_option(
      "--topic", options->topic,
      "Bag topic of velodyne_msgs/VelodyneScan or sensor_msgs/PointCloud2 (default: the "
      "only one)");
  cmd->add_option("--out", options->out_path, "Output trajectory (TUM, UTC time stamps)")
      ->required();
  cmd->add_option("--details", options->details_path, "Per-scan diagnostics (CSV)");
  cmd->add_option("--covariance", options->covariance_path,
                  "Per-scan pose covariance (CSV: time_s and the 21 upper-triangle entries over "
                  "x, y, z, roll, pitch, yaw; m², m·rad, rad²)");
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
  cmd->add_option("--adaptive-ess", options->config.filter.adaptive_ess_fraction,
                  "Adaptive tempering: keep the conditional ESS above this fraction (0: off)");
  cmd->add_option(
         "--reference-terms", options->config.filter.reference_terms,
         "A scan counts as at most this many independent terms (0: what its surfaces are worth)")
      ->capture_default_str();
  cmd->add_option("--height", options->height_m, "Sensor height above the floor for --global (m)")
      ->capture_default_str();
  cmd->add_option("--sensor-model", options->sensor_model,
                  "vlp16, puck-lite, puck-hires, hdl32e, vlp32c")
      ->capture_default_str();
  cmd->add_option("--calibration", options->calibration_xml,
                  "VeloView XML calibration (default: the model's built-in table)")
      ->check(CLI::ExistingFile);
  cmd->add_flag("!--no-deskew", options->config.deskew, "Do not de-skew scans");
  cmd->add_option("--min-partial", options->min_partial_fraction,
                  "Skip a capture's cut-short first/last scan covering less than this fraction of "
                  "a rotation (0 keeps all)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->callback([options] { run_localize(*options); });
}

}  // namespace conicloc::tools
