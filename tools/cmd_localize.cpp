// `conicloc localize --map building.gml --pcap run.pcap --out poses.tum`: a pose per scan, of a
// capture or (`--udp [ADDR:]PORT`) of a live sensor.
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <thread>

#include "io/indoorgml.hpp"
#include "io/input_error.hpp"
#include "io/live_scan_source.hpp"
#include "io/tum_trajectory.hpp"
#include "io/udp_sender.hpp"
#include "io/veloview_calibration.hpp"
#include "localizer/filter/localizer.hpp"
#include "localizer/models/observation_factory.hpp"
#include "parallel/parallel_for.hpp"
#include "run/localize_run.hpp"
#include "sensor/builtin_calibration.hpp"
#include "tools/capture_report.hpp"
#include "tools/commands.hpp"
#include "tools/details_csv.hpp"
#include "tools/map_options.hpp"
#include "tools/number_list.hpp"
#include "tools/pose_json.hpp"
#include "tools/process_memory.hpp"
#include "tools/report_recorder.hpp"
#include "tools/run_recording.hpp"
#include "tools/sensor_option.hpp"
#include "tools/status_log.hpp"

namespace conicloc::tools {
namespace {

// A live sensor instead of a capture.
struct LiveOptions {
  std::string udp;                                  ///< "[ADDR:]PORT" to listen on; "" reads --pcap
  int position_port = io::velodyne::kPositionPort;  ///< 0: not listened for
  double idle_timeout_s = 5.0;                      ///< 0: wait forever
  std::size_t queue_depth = 2;
  int throttle_ms = 0;   ///< testing: sleep this long after every update
  std::string pose_udp;  ///< "HOST:PORT" for a JSON line per scan
};

struct LocalizeOptions {
  std::string map_path;
  std::string pcap_path;
  LiveOptions live;
  std::string topic;
  std::string sensor;  ///< "[ADDR:]PORT" of the sensor in a capture of several ("": port 2368)
  std::string out_path;
  std::string details_path;
  std::string covariance_path;
  std::string report_dir;
  std::size_t report_every = 10;
  std::string record_path;
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

// Ctrl-C ends a live run cleanly, with its summary (the handler may only touch a lock-free
// atomic; stop() only stores an atomic flag).
std::atomic<io::LiveScanSource*> g_live_source{nullptr};
extern "C" void stop_live_source(int) {
  if (auto* source = g_live_source.load()) source->stop();
}

// Ctrl-C stops `source` while this lives.
class StopOnInterrupt {
 public:
  explicit StopOnInterrupt(io::LiveScanSource& source) {
    g_live_source.store(&source);
    std::signal(SIGINT, stop_live_source);
  }
  ~StopOnInterrupt() {
    std::signal(SIGINT, SIG_DFL);
    g_live_source.store(nullptr);
  }
  StopOnInterrupt(const StopOnInterrupt&) = delete;
  StopOnInterrupt& operator=(const StopOnInterrupt&) = delete;
};

std::unique_ptr<io::LiveScanSource> open_live_source(const LiveOptions& o,
                                                     const sensor::LaserCalibration& calibration) {
  io::LiveSourceConfig config;
  config.receiver.listen = io::parse_listen_endpoint(o.udp, "--udp");
  if (o.position_port > 0) config.receiver.position_port = o.position_port;
  config.receiver.idle_timeout_s = o.idle_timeout_s;
  config.queue_depth = o.queue_depth;
  auto source = std::make_unique<io::LiveScanSource>(calibration, config);
  spdlog::info("listening on {}{} (idle timeout {}, Ctrl-C to stop)", source->name(),
               source->position_port()
                   ? fmt::format(", position packets on port {}", *source->position_port())
                   : "",
               o.idle_timeout_s > 0 ? fmt::format("{} s", o.idle_timeout_s) : "off");
  return source;
}

void log_live_summary(const io::LiveScanSource& live, const run::LocalizeRunSummary& summary) {
  const auto& stats = summary.stream;
  spdlog::info(
      "{}: {} whole scans received: {} localized, {} dropped while the filter was busy, {} "
      "partial skipped",
      live.name(), live.assembled_scans(), summary.scans, live.dropped_scans(),
      summary.skipped_partial);
  spdlog::info(
      "{}: {} datagrams: {} data packets decoded, {} position packets, {} bad datagrams ({} data, "
      "{} position), ~{} packets lost",
      live.name(), summary.capture.udp_datagrams, stats.data_packets, stats.position_packets,
      stats.rejected_total() + stats.bad_position_packets, stats.rejected_total(),
      stats.bad_position_packets, stats.packets_lost);
  if (stats.rejected_total() > summary.first_rejections.size()) {
    spdlog::warn("{}: {} more rejected data packets not listed", live.name(),
                 stats.rejected_total() - summary.first_rejections.size());
  }
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

  const auto loaded = load_map(o.map_path, o.map_options);
  if (!o.trust_units) require_plausible_units(o.map_path, loaded, o.map_options);
  const maps::PlaneMap& map = loaded.map;
  spdlog::info("map {}: {} polygons, {} cells", o.map_path, map.polygons.size(), map.cells.size());

  run::LocalizeRunConfig run;
  run.pcap_path = o.pcap_path;
  run.topic = o.topic;
  run.calibration = sensor::builtin_calibration(*model);
  if (!o.calibration_xml.empty()) {
    auto calibration = io::read_veloview_calibration(o.calibration_xml, *model);
    for (const auto& warning : calibration.warnings) spdlog::warn("{}", warning);
    run.calibration = calibration.calibration;
    spdlog::info("calibration from {}", o.calibration_xml);
  }
  if (!o.sensor.empty()) apply_sensor_option(o.sensor, "--sensor", run.stream);
  run.localizer = o.config;
  run.localizer.motion.height_above_floor_m = o.height_m;
  run.two_sided_walls = loaded.report.two_sided_faces > 0;
  run.min_partial_fraction = o.min_partial_fraction;
  if (!o.init_text.empty() && !o.global) {
    const auto init = parse_numbers(o.init_text, 4, "--init");
    const auto sigma = parse_numbers(o.init_sigma_text, 3, "--init-sigma");
    run.start =
        run::start_around(localizer::make_pose(init[0], init[1], init[2], init[3] * M_PI / 180.0),
                          sigma[0], sigma[1], sigma[2] * M_PI / 180.0);
  } else {
    run.start.global = true;
  }
  if (!o.odom_path.empty()) run.odometry = io::read_tum(o.odom_path);
  // The sensor before the filter: a port that cannot be bound is reported before any filter work.
  std::unique_ptr<io::LiveScanSource> live;
  if (!o.live.udp.empty()) live = open_live_source(o.live, run.calibration);
  std::unique_ptr<io::UdpSender> pose_sender;
  if (!o.live.pose_udp.empty()) {
    pose_sender =
        std::make_unique<io::UdpSender>(io::parse_send_endpoint(o.live.pose_udp, "--pose-udp"));
    spdlog::info("poses as JSON lines to {}", pose_sender->name());
  }
  spdlog::info("model {}, {} start, {} threads, seed {}", run.localizer.observation.model,
               run.start.global ? "global" : "tracking",
               conicloc::resolve_thread_count(run.localizer.threads), run.localizer.seed);

  std::ofstream out_file;
  if (o.out_path != "-") {
    out_file.open(o.out_path);
    if (!out_file) throw io::InputError(o.out_path, "", "cannot open for writing");
  }
  std::ostream& out = o.out_path == "-" ? std::cout : out_file;
  std::ofstream details;
  if (!o.details_path.empty()) {
    details.open(o.details_path);
    if (!details) throw io::InputError(o.details_path, "", "cannot open for writing");
    details << details_header() << "\n";
  }
  std::ofstream covariance;
  if (!o.covariance_path.empty()) {
    covariance.open(o.covariance_path);
    if (!covariance) throw io::InputError(o.covariance_path, "", "cannot open for writing");
    covariance << covariance_header() << "\n";
  }
  std::optional<ReportRecorder> recorder;
  if (!o.report_dir.empty()) {
    recorder.emplace(o.report_dir, map, run.calibration,
                     ReportRecorderConfig{.frame_every = o.report_every, .limits = {}});
  }
  std::optional<RunRecording> recording;
  if (!o.record_path.empty()) {
    RecordingOptions recording_options;
    recording_options.cull_back_faces = !run.two_sided_walls;
    recording.emplace(o.record_path, map, run.calibration, recording_options);
  }
  StatusLog status_log;
  Progress progress;
  std::size_t scans = 0;
  double first_time = 0.0;
  const auto on_scan = [&](double utc_s, const localizer::UpdateResult& r) {
    if (scans++ == 0) first_time = utc_s;
    status_log.update(utc_s - first_time, r);
    // Flushed per scan: a consumer (a pipe, `tail -f`) has every pose as soon as it exists.
    io::write_tum_line(out, {utc_s, r.pose});
    out.flush();
    if (pose_sender) pose_sender->send(pose_json_line(utc_s, r));
    if (live) {
      for (const auto& rejected : live->take_rejections())
        log_rejected_packet(live->name(), rejected, true);
    }
    if (details.is_open()) details << details_row(utc_s, r);
    if (covariance.is_open()) covariance << covariance_row(utc_s, r.covariance) << "\n";
    progress.update(scans, utc_s - first_time, r);
    if (o.live.throttle_ms > 0)
      std::this_thread::sleep_for(std::chrono::milliseconds(o.live.throttle_ms));
  };
  const auto on_state = [&](double utc_s, const localizer::UpdateResult& r,
                            const run::ScanState& state) {
    if (recorder) recorder->record(utc_s, r, state);
    if (recording) recording->add(utc_s, r, state.scan, state.particles);
  };
  run::LocalizeRunSummary summary;
  if (live) {
    {
      const StopOnInterrupt interrupt(*live);
      summary = run::run_localization(map, run, *live, on_scan, on_state);
    }
    for (const auto& rejected : live->take_rejections())
      log_rejected_packet(live->name(), rejected, true);
  } else {
    summary = run::run_localization(map, run, on_scan, on_state);
  }
  progress.finish();
  status_log.finish();

  const std::string input = live ? live->name() : o.pcap_path;
  for (const auto& warning : summary.stream_warnings) spdlog::warn("{}: {}", input, warning);
  if (live) {
    log_live_summary(*live, summary);
  } else {
    log_capture_problems(o.pcap_path, &summary.capture, summary.stream, summary.first_rejections);
  }
  const auto& stats = summary.stream;
  spdlog::info(
      "{} scans localized ({} partial scans empty or under half a rotation skipped), {} "
      "recoveries",
      summary.scans, summary.skipped_partial, summary.recoveries);
  if (summary.plan_search_bytes > 0)
    spdlog::info("global start: {:.0f} ms, the plan search's fields built ({:.1f} MiB)",
                 summary.start_time_ms,
                 static_cast<double>(summary.plan_search_bytes) / (1024.0 * 1024.0));
  if (summary.scans > 0) {
    spdlog::info(
        "time per scan: mean {:.1f} ms, p95 {:.1f} ms, max {:.1f} ms; real-time factor "
        "{:.1f}x",
        summary.mean_time_ms(), summary.quantile_time_ms(0.95), summary.max_time_ms(),
        summary.realtime_factor());
  }
  if (live) {
    // The live summary above says it all.
  } else if (summary.point_clouds) {
    spdlog::info("point clouds: {} messages read, {} skipped; {} truncated capture records",
                 summary.capture.records, summary.capture.bad_messages,
                 summary.capture.truncated_records);
  } else {
    spdlog::info("packets: {} decoded, {} rejected, ~{} lost; {} truncated capture records",
                 stats.data_packets, stats.rejected_total(), stats.packets_lost,
                 summary.capture.truncated_records);
    if (stats.other_senders > 0) {
      spdlog::info("{} datagrams from other senders on the sensor's ports left out (--sensor {})",
                   stats.other_senders, sensor_text(run.stream));
    }
  }
  if (recording) {
    recording->close();
    spdlog::info("recording: {} messages written to {}", recording->messages(), o.record_path);
  }
  spdlog::info("peak memory {:.1f} MiB; poses written to {}", peak_rss_mib(), o.out_path);
  if (recorder) {
    recorder->finish(summary, {.capture = o.pcap_path,
                               .model = run.localizer.observation.model,
                               .global = run.start.global});
    spdlog::info(
        "report data ({} frames, one every {} scans) in {}; draw it with `conicloc report --map {} "
        "--report-dir {} --out run.html`",
        recorder->frames(), o.report_every, o.report_dir, o.map_path, o.report_dir);
  }
  if (summary.scans == 0) throw CLI::RuntimeError(2);
}

}  // namespace

void add_localize_command(CLI::App& app) {
  auto options = std::make_shared<LocalizeOptions>();
  options->map_path = example_map_path();
  auto* cmd = app.add_subcommand(
      "localize", "Estimate the sensor pose at every scan of a capture or a live sensor");
  cmd->add_option("--map", options->map_path, "IndoorGML building model")->check(CLI::ExistingFile);
  add_map_load_options(cmd, options->map_options);
  cmd->add_flag("--trust-units", options->trust_units,
                "Localize even when the map's storey heights or extent look like other units");
  auto* pcap =
      cmd->add_option("--pcap,--capture", options->pcap_path,
                      "Capture of the sensor: pcap/pcapng, or a ROS bag of "
                      "velodyne_msgs/VelodyneScan or sensor_msgs/PointCloud2 (MCAP, ROS 2 .db3 "
                      "file or folder, ROS 1 .bag), recognised by content")
          ->check(CLI::ExistingPath);
  auto* udp = cmd->add_option("--udp", options->live.udp,
                              "Live sensor: listen for its data packets on [ADDR:]PORT (IPv4; "
                              "2368 for a Velodyne)");
  pcap->excludes(udp);
  cmd->add_option("--sensor", options->sensor,
                  "The sensor of a capture that holds several: [ADDR:]PORT of its data packets "
                  "(sender address, destination port; default: port 2368, any sender)")
      ->excludes(udp);
  cmd->add_option("--position-port", options->live.position_port,
                  "With --udp: also read position packets on this port (0: do not listen)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  cmd->add_option("--idle-timeout", options->live.idle_timeout_s,
                  "With --udp: end after this many seconds without a datagram (0: wait forever)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--queue-depth", options->live.queue_depth,
                  "With --udp: whole scans waiting for the filter; when full the oldest is "
                  "dropped and counted")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->add_option("--throttle-ms", options->live.throttle_ms,
                  "Testing: sleep this long after every update (to make the filter fall behind)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--pose-udp", options->live.pose_udp,
                  "Also send every pose as one JSON line (time, pose, covariance, status) to "
                  "HOST:PORT");
  cmd->add_option(
      "--topic", options->topic,
      "Bag topic of velodyne_msgs/VelodyneScan or sensor_msgs/PointCloud2 (default: the "
      "only one)");
  cmd->add_option("--out", options->out_path,
                  "Output trajectory (TUM, UTC time stamps; '-': stdout), flushed per scan")
      ->required();
  cmd->add_option("--details", options->details_path, "Per-scan diagnostics (CSV)");
  cmd->add_option("--covariance", options->covariance_path,
                  "Per-scan pose covariance (CSV: time_s and the 21 upper-triangle entries over "
                  "x, y, z, roll, pitch, yaw; m², m·rad, rad²)");
  cmd->add_option("--report-dir", options->report_dir,
                  "Write what `conicloc report` draws into this folder: poses, details, sampled "
                  "frames (particles, returns, predicted conics) and the run's summary");
  cmd->add_option("--report-every", options->report_every,
                  "With --report-dir: a frame every this many scans")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--record", options->record_path,
                  "Recording for Foxglove / Lichtblick (MCAP): map, scans, particles, estimate, "
                  "predicted conics, frame transforms");
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
  cmd->add_option(
         "--refine-hypotheses", options->config.filter.refinement.hypotheses,
         "While searching, hypotheses climbed onto their likelihood peak per scan (0: off)")
      ->capture_default_str();
  cmd->add_option("--runner-ups", options->config.filter.runner_ups.max_runner_ups,
                  "Until a global start or recovery has converged, runner-up modes kept alive "
                  "through resampling beside the leader (0: off)")
      ->check(CLI::Range(0, 16))
      ->capture_default_str();
  cmd->add_flag("!--no-storey-twins", options->config.storey_twins.enabled,
                "Once a global start or recovery has converged, do not weigh the estimate's "
                "copies on the other storeys (identical storeys are then called from the "
                "cloud's weights alone)");
  cmd->add_option("--repropose-every", options->config.missing_hypotheses.every_scans,
                  "While a global start or recovery searches, search the floor plan again every "
                  "this many scans and add the places the scan fits that the cloud lacks (0: off; "
                  "needs --plan-search > 0)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--search-rings", options->config.search_rings,
                  "While a global start or recovery searches the building, rings scored, spread "
                  "over the elevations (0: all)")
      ->capture_default_str();
  cmd->add_option("--headings-per-position", options->config.filter.headings_per_position,
                  "A global start draws each position for this many particles, their headings "
                  "spread over the first scan's proposal; one prediction serves them all (1: a "
                  "position per particle)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  cmd->add_option("--init-particles", options->config.filter.initial_particles,
                  "Particles for --init; a start wide enough to be searched (position std. dev. "
                  "over 0.25 m) takes --particles")
      ->capture_default_str();
  cmd->add_option("--threads", options->config.threads, "Worker threads (0: all cores)")
      ->capture_default_str();
  cmd->add_option("--seed", options->config.seed, "Random seed (runs repeat exactly)")
      ->capture_default_str();
  for (const auto& model : localizer::observation_models()) {
    if (!model.max_beams) continue;
    cmd->add_option(model.max_beams_option, model.max_beams(options->config.observation),
                    model.max_beams_help)
        ->capture_default_str();
  }
  cmd->add_option("--tempering", options->config.filter.tempering, "Likelihood exponent")
      ->capture_default_str();
  cmd->add_option("--adaptive-ess", options->config.filter.adaptive_ess_fraction,
                  "Adaptive tempering: keep the conditional ESS above this fraction (0: off)");
  cmd->add_option("--tracking-ess", options->config.filter.tracking_ess_fraction,
                  "A tracked cloud's floor: a scan is tempered to keep at least this fraction "
                  "of the particles effective (0: full exponent)")
      ->capture_default_str();
  cmd->add_option(
         "--reference-terms", options->config.filter.reference_terms,
         "A scan counts as at most this many independent terms (0: what its surfaces are worth)")
      ->capture_default_str();
  cmd->add_option("--plan-search", options->config.plan_search.fraction,
                  "Share of a global start's particles (and of a restart's over the whole "
                  "building) drawn where the scan fits the floor plan; the rest, and all where "
                  "it fits nowhere, uniform over the free space (0: all uniform)")
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
  cmd->add_flag("!--no-surface-weights", options->config.surface_weights,
                "Give every beam (segment return) of a scan one exponent, also where the "
                "surfaces facing a direction hold few of them (the conic models; see the README)");
  cmd->add_option("--min-partial", options->min_partial_fraction,
                  "Skip a capture's cut-short first/last scan covering less than this fraction of "
                  "a rotation (0 keeps all)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->callback([options, pcap, udp] {
    if (pcap->count() == 0 && udp->count() == 0)
      throw CLI::RequiredError("--pcap or --udp (a capture or a live sensor)");
    run_localize(*options);
  });
}

}  // namespace conicloc::tools
