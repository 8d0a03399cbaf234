// `conicloc calibrate --map building.gml --pcap run.pcap --out calibration.xml --report
// calibration.json`: per-laser intrinsics and the mounting from scans of the map's planes.
//
// Pipeline: decode with the given (or built-in) calibration → localize every scan
// (run_localization) → take a subset of scans after the filter settled → their returns, each
// with its de-skew motion from the localized trajectory → calib::calibrate (corrections,
// mounting and the scans' planar poses jointly) → VeloView XML and a JSON report.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "calib/calibration_solver.hpp"
#include "calib/truth_comparison.hpp"
#include "io/input_error.hpp"
#include "io/scan_source.hpp"
#include "io/velodyne_packet.hpp"
#include "io/veloview_calibration.hpp"
#include "localizer/filter/relative_motion.hpp"
#include "run/localize_run.hpp"
#include "sensor/builtin_calibration.hpp"
#include "tools/commands.hpp"
#include "tools/json_writer.hpp"
#include "tools/map_options.hpp"
#include "tools/number_list.hpp"

namespace conicloc::tools {
namespace {

constexpr double kDeg = 180.0 / M_PI;

struct CalibrateOptions {
  std::string map_path;
  std::string pcap_path;
  std::string topic;
  std::string out_path;
  std::string report_path;
  std::string calibration_xml;
  std::string truth_xml;
  std::string sensor_model = "vlp16";
  std::string init_text;
  std::string init_sigma_text = "0.2,0.2,5";
  std::string init_tilt_text = "0,0";  ///< "roll_deg,pitch_deg" of the start pose
  bool global = false;
  double height_m = 0.8;
  int settle_scans = 10;     ///< scans left to the filter before any is used
  int max_scans = 20;        ///< scans used, spread evenly over the rest
  int return_stride = 4;     ///< every n-th return of a ring
  double min_range_m = 0.5;  ///< nearer returns are left out (blind zone, the carrier)
  io::MapLoadOptions map_options;
  localizer::LocalizerConfig localizer;
  calib::CalibrationConfig calibration;
};

struct LocalizedScan {
  double utc_s = 0.0;
  localizer::Pose3 T_map_sensor;
};

// The floor under a sensor: the highest storey floor at or below it.
double floor_below(const maps::PlaneMap& map, double z_m) {
  double floor = map.storeys.empty() ? map.bounds.min().z() : map.storeys.front().floor_z;
  for (const auto& storey : map.storeys) {
    if (storey.floor_z <= z_m) floor = std::max(floor, storey.floor_z);
  }
  return floor;
}

struct Observations {
  std::vector<calib::Return> returns;
  std::vector<calib::ScanPose> poses;
  calib::Mounting mounting;
};

// Re-reads the capture and gathers the returns of the chosen scans, matched to their localized
// poses by time. A return fired at t is de-skewed by the localized motion from the previous scan,
// scaled to (t − t_scan)/interval (constant velocity).
Observations gather(const CalibrateOptions& o, const maps::PlaneMap& map,
                    const sensor::LaserCalibration& calibration,
                    const std::vector<LocalizedScan>& localized) {
  Observations out;
  if (localized.size() < 2 + static_cast<std::size_t>(o.settle_scans)) {
    throw CLI::ValidationError("--pcap", "only " + std::to_string(localized.size()) +
                                             " scans localized; calibration needs more than " +
                                             std::to_string(o.settle_scans + 1));
  }
  std::vector<std::size_t> chosen;
  const std::size_t first = static_cast<std::size_t>(o.settle_scans) + 1;
  const std::size_t available = localized.size() - first;
  const std::size_t count = std::min<std::size_t>(available, static_cast<std::size_t>(o.max_scans));
  for (std::size_t i = 0; i < count; ++i) chosen.push_back(first + i * available / count);

  io::ScanSourceOptions source_options;
  source_options.capture.topic = o.topic;
  const auto source = io::open_scan_source(o.pcap_path, calibration, source_options);
  std::size_t next = 0;
  double height_sum = 0.0, roll_sum = 0.0, pitch_sum = 0.0;
  while (next < chosen.size()) {
    const auto scan = source->next();
    if (!scan) break;
    const double utc_s = scan->end_time_s + source->utc_offset_s().value_or(0.0);
    const LocalizedScan& target = localized[chosen[next]];
    if (std::abs(utc_s - target.utc_s) > 1e-6) continue;
    const LocalizedScan& previous = localized[chosen[next] - 1];
    const double interval_s = target.utc_s - previous.utc_s;
    const localizer::ConstantVelocityMotion motion(previous.T_map_sensor.inverse() *
                                                   target.T_map_sensor);
    const int scan_index = static_cast<int>(out.poses.size());
    const Eigen::Vector3d t = target.T_map_sensor.translation();
    const double floor_z = floor_below(map, t.z());
    out.poses.push_back({t.x(), t.y(), localizer::yaw_of(target.T_map_sensor), floor_z});
    height_sum += t.z() - floor_z;
    // R = Rz(yaw)·Ry(pitch)·Rx(roll): the pitch and roll the localizer gave, mean over scans.
    const Eigen::Matrix3d R = target.T_map_sensor.linear();
    pitch_sum += std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
    roll_sum += std::atan2(R(2, 1), R(2, 2));
    for (const auto& ring : scan->rings) {
      int seen = 0;
      for (const auto& ret : ring.returns) {
        if (ret.status != sensor::ReturnStatus::Valid || ret.range_m < o.min_range_m) continue;
        if (seen++ % o.return_stride != 0) continue;
        calib::Return r;
        r.laser = ring.channel;
        r.scan = scan_index;
        r.azimuth_rad = ret.azimuth_rad;
        r.range_m = ret.range_m;
        r.T_ref_fire = interval_s > 0 ? motion.at((ret.time_s - scan->end_time_s) / interval_s)
                                      : Eigen::Isometry3d::Identity();
        out.returns.push_back(r);
      }
    }
    ++next;
  }
  if (out.poses.empty()) {
    throw io::InputError(o.pcap_path, "scans", "no localized scan found on the second read");
  }
  const auto n = static_cast<double>(out.poses.size());
  out.mounting = {height_sum / n, roll_sum / n, pitch_sum / n};
  return out;
}

void write_report(const std::string& path, const CalibrateOptions& o, const maps::PlaneMap& map,
                  const sensor::LaserCalibration& decode, const calib::CalibrationResult& result,
                  const std::optional<calib::TruthErrors>& truth) {
  constexpr std::array<const char*, 4> kNames = {"elevation_deg", "vertical_offset_m",
                                                 "azimuth_offset_deg", "range_offset_m"};
  constexpr std::array<double, 4> kScale = {kDeg, 1.0, kDeg, 1.0};
  std::ofstream out(path);
  JsonWriter j(out);
  j.begin_object();
  j.key("tool").value("conicloc calibrate");
  j.key("map").value(o.map_path);
  j.key("pcap").value(o.pcap_path);
  j.key("decode_calibration").value(o.calibration_xml.empty() ? "built-in" : o.calibration_xml);
  j.key("scans").value(static_cast<int>(result.poses.size()));
  j.key("returns").value(static_cast<unsigned long>(result.returns));
  j.key("rms_m").value(result.rms_m);
  j.key("sigma_m").value(result.sigma_m);
  j.key("iterations").value(result.iterations);
  j.key("converged").value(result.converged);
  j.key("gauge").value(
      "mean vertical offset and mean azimuth offset corrections are 0 over the "
      "lasers observing them");
  j.key("lasers").begin_array();
  for (std::size_t k = 0; k < result.lasers.size(); ++k) {
    const calib::LaserEstimate& e = result.lasers[k];
    const sensor::Laser& d = decode.lasers[k];
    const std::array<double, 4> value = {d.elevation_rad + e.correction.elevation_rad,
                                         d.vertical_offset_m + e.correction.vertical_offset_m,
                                         d.azimuth_offset_rad + e.correction.azimuth_rad,
                                         d.range_offset_m + e.correction.range_m};
    j.begin_object();
    j.key("laser_id").value(static_cast<int>(k));
    j.key("ring").value(d.ring);
    for (int i = 0; i < 4; ++i) {
      const bool known = e.observability.observable[i];
      j.key(kNames[i]);
      known ? j.value(value[i] * kScale[i]) : j.null();
      const std::string name = kNames[i];
      const std::string sigma_name =
          name.substr(0, name.rfind('_')) + "_sigma" + name.substr(name.rfind('_'));
      j.key(sigma_name);
      known ? j.value(e.sigma[i] * kScale[i]) : j.null();
    }
    j.key("observable").value(e.observability.all());
    if (!e.observability.all()) j.key("missing").value(e.observability.missing);
    j.key("returns").value(e.returns);
    j.key("planes").value(e.planes);
    j.end_object();
  }
  j.end_array();
  j.key("mounting").begin_object();
  j.key("height_m").value(result.mounting.height_m);
  j.key("height_sigma_m").value(result.mounting_sigma[0]);
  j.key("roll_deg").value(result.mounting.roll_rad * kDeg);
  j.key("roll_sigma_deg").value(result.mounting_sigma[1] * kDeg);
  j.key("pitch_deg").value(result.mounting.pitch_rad * kDeg);
  j.key("pitch_sigma_deg").value(result.mounting_sigma[2] * kDeg);
  j.end_object();
  // Where the surfaces the returns fell on stand against the map (plane adjustment), each up
  // to the map's common shift, which only the prior holds (calibration_solver.hpp).
  j.key("map_sigma_m").value(o.calibration.map_sigma_m);
  j.key("map_planes").begin_array();
  for (const calib::PlaneEstimate& plane : result.planes) {
    j.begin_object();
    j.key("polygon").value(plane.polygon);
    j.key("source_id").value(map.polygons[plane.polygon].source_id);
    j.key("offset_m").value(plane.correction.offset_m);
    j.key("offset_sigma_m").value(plane.sigma[0]);
    j.key("tilt_u_deg").value(std::atan(plane.correction.slope_u) * kDeg);
    j.key("tilt_u_sigma_deg").value(plane.sigma[1] * kDeg);
    j.key("tilt_v_deg").value(std::atan(plane.correction.slope_v) * kDeg);
    j.key("tilt_v_sigma_deg").value(plane.sigma[2] * kDeg);
    j.key("returns").value(plane.returns);
    j.end_object();
  }
  j.end_array();
  if (truth) {
    j.key("truth").begin_object();
    j.key("file").value(o.truth_xml);
    j.key("elevation_rms_deg").value(truth->elevation_rms_rad * kDeg);
    j.key("vertical_offset_rms_mm").value(truth->vertical_offset_rms_m * 1000.0);
    j.key("azimuth_offset_rms_deg").value(truth->azimuth_rms_rad * kDeg);
    j.key("range_offset_rms_mm").value(truth->range_offset_rms_m * 1000.0);
    // Per correction, in the order elevation, vertical offset, azimuth offset, range offset.
    j.key("compared").begin_array();
    for (const int n : truth->compared) j.value(n);
    j.end_array();
    j.key("unobservable").begin_array();
    for (const int n : truth->unobservable) j.value(n);
    j.end_array();
    j.end_object();
  }
  j.end_object();
  out << '\n';
  if (!out) throw io::InputError(path, "", "cannot write the calibration report");
}

void run_calibrate(const CalibrateOptions& o) {
  const auto model = sensor::parse_sensor_model(o.sensor_model);
  if (!model)
    throw CLI::ValidationError("--sensor-model", "unknown sensor model '" + o.sensor_model + "'");
  if (o.return_stride < 1) throw CLI::ValidationError("--return-stride", "must be at least 1");
  const auto loaded = load_map(o.map_path, o.map_options);
  const maps::PlaneMap& map = loaded.map;

  run::LocalizeRunConfig run;
  run.pcap_path = o.pcap_path;
  run.topic = o.topic;
  run.calibration = sensor::builtin_calibration(*model);
  if (!o.calibration_xml.empty()) {
    auto calibration = io::read_veloview_calibration(o.calibration_xml, *model);
    for (const auto& warning : calibration.warnings) spdlog::warn("{}", warning);
    run.calibration = calibration.calibration;
  }
  run.localizer = o.localizer;
  run.localizer.motion.height_above_floor_m = o.height_m;
  run.two_sided_walls = loaded.report.two_sided_faces > 0;
  if (!o.init_text.empty() && !o.global) {
    const auto init = parse_numbers(o.init_text, 4, "--init");
    const auto sigma = parse_numbers(o.init_sigma_text, 3, "--init-sigma");
    const auto tilt = parse_numbers(o.init_tilt_text, 2, "--init-tilt");
    run.start.pose = localizer::make_pose(init[0], init[1], init[2], init[3] * M_PI / 180.0,
                                          tilt[1] * M_PI / 180.0, tilt[0] * M_PI / 180.0);
    run.start.sigma << sigma[0], sigma[1], 0.02, 0.01, 0.01, sigma[2] * M_PI / 180.0;
  } else {
    run.start.global = true;
  }
  std::vector<LocalizedScan> localized;
  run::run_localization(map, run, [&](double utc_s, const localizer::UpdateResult& r) {
    localized.push_back({utc_s, r.pose});
  });
  spdlog::info("{} scans localized", localized.size());

  const Observations observations = gather(o, map, run.calibration, localized);
  spdlog::info("{} returns of {} scans; start height {:.3f} m, roll {:.2f}°, pitch {:.2f}°",
               observations.returns.size(), observations.poses.size(),
               observations.mounting.height_m, observations.mounting.roll_rad * kDeg,
               observations.mounting.pitch_rad * kDeg);
  const calib::CalibrationResult result =
      calib::calibrate(map, run.calibration, observations.returns, observations.mounting,
                       observations.poses, o.calibration);
  spdlog::info("{} returns on planes, residual rms {:.4f} m, {} iterations{}", result.returns,
               result.rms_m, result.iterations, result.converged ? "" : " (not converged)");
  for (std::size_t k = 0; k < result.lasers.size(); ++k) {
    const auto& e = result.lasers[k];
    if (!e.observability.all()) spdlog::warn("laser {}: {}", k, e.observability.missing);
  }
  if (!result.planes.empty()) {
    spdlog::info("{} map planes adjusted (prior {:.3f} m)", result.planes.size(),
                 o.calibration.map_sigma_m);
  }
  spdlog::info("mounting: height {:.4f} ± {:.4f} m, roll {:.3f} ± {:.3f}°, pitch {:.3f} ± {:.3f}°",
               result.mounting.height_m, result.mounting_sigma[0], result.mounting.roll_rad * kDeg,
               result.mounting_sigma[1] * kDeg, result.mounting.pitch_rad * kDeg,
               result.mounting_sigma[2] * kDeg);

  std::vector<calib::LaserCorrection> corrections;
  for (const auto& e : result.lasers) corrections.push_back(e.correction);
  io::write_veloview_calibration(o.out_path, calib::corrected(run.calibration, corrections),
                                 io::velodyne::packet_layout(*model).distance_unit_m);
  std::optional<calib::TruthErrors> truth;
  if (!o.truth_xml.empty()) {
    const auto true_calibration = io::read_veloview_calibration(o.truth_xml, *model).calibration;
    truth = calib::compare_to_truth(result, run.calibration, true_calibration);
    spdlog::info(
        "against {}: rms elevation {:.4f}°, vertical offset {:.2f} mm, azimuth {:.4f}°, range "
        "offset {:.2f} mm",
        o.truth_xml, truth->elevation_rms_rad * kDeg, truth->vertical_offset_rms_m * 1000.0,
        truth->azimuth_rms_rad * kDeg, truth->range_offset_rms_m * 1000.0);
  }
  if (!o.report_path.empty()) write_report(o.report_path, o, map, run.calibration, result, truth);
  spdlog::info("calibration written to {}", o.out_path);
}

}  // namespace

void add_calibrate_command(CLI::App& app) {
  auto o = std::make_shared<CalibrateOptions>();
  o->map_path = example_map_path();
  auto* cmd = app.add_subcommand(
      "calibrate", "Per-laser calibration and mounting from a capture in a mapped building");
  cmd->add_option("--map", o->map_path, "IndoorGML building model")->check(CLI::ExistingFile);
  add_map_load_options(cmd, o->map_options);
  cmd->add_option("--pcap,--capture", o->pcap_path,
                  "Capture of the sensor (any format localize reads)")
      ->required()
      ->check(CLI::ExistingPath);
  cmd->add_option("--topic", o->topic, "Bag topic (default: the only one)");
  cmd->add_option("--out", o->out_path, "Calibration to write (VeloView XML)")->required();
  cmd->add_option("--report", o->report_path, "Estimates, sigmas and observability (JSON)");
  cmd->add_option("--calibration", o->calibration_xml,
                  "Calibration to decode with and start from (default: built-in)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--truth", o->truth_xml,
                  "True calibration (simulate --calib-truth-xml): print the RMS errors")
      ->check(CLI::ExistingFile);
  cmd->add_option("--sensor-model", o->sensor_model, "vlp16, puck-lite, puck-hires, hdl32e, vlp32c")
      ->capture_default_str();
  cmd->add_option("--init", o->init_text, "Initial pose x,y,z,yaw_deg (map frame)");
  cmd->add_option("--init-sigma", o->init_sigma_text, "Initial std. dev. sigma_x,sigma_y,yaw_deg")
      ->capture_default_str();
  cmd->add_option("--init-tilt", o->init_tilt_text,
                  "Roll and pitch of the start pose, roll_deg,pitch_deg (a tilted mount)")
      ->capture_default_str();
  cmd->add_flag("--global", o->global, "Global localization over all navigable cells");
  cmd->add_option("--height", o->height_m, "Sensor height above the floor for the filter (m)")
      ->capture_default_str();
  cmd->add_option("--settle-scans", o->settle_scans, "Scans left to the filter before use")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--scans", o->max_scans, "Scans used, spread over the capture")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--return-stride", o->return_stride, "Use every n-th return of a ring")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--map-sigma", o->calibration.map_sigma_m,
                  "How far the map's planes may stand off (m): each plane seen is adjusted with "
                  "this prior (0: planes fixed)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--threads", o->localizer.threads, "Localizer threads (0: all cores)")
      ->capture_default_str();
  cmd->add_option("--seed", o->localizer.seed, "Localizer random seed")->capture_default_str();
  cmd->callback([o] { run_calibrate(*o); });
}

}  // namespace conicloc::tools
