// `conicloc calibrate --map building.gml --pcap run.pcap --out calibration.xml --report
// calibration.json`: per-laser intrinsics and the mounting from scans of the map's planes.
//
// Pipeline: decode with the given (or built-in) calibration → localize every scan
// (run_localization) → take a subset of scans after the filter settled → their returns, each
// with its firing time in its scan, and each scan's pose and velocity from the localized
// trajectory to start from → calib::calibrate (corrections, mounting, the scans' planar poses
// and velocities jointly) → VeloView XML and a JSON report.
// With --second-sensor: the second sensor's returns fired within the same scans, carried by the
// first sensor's calibrated poses and motion → calib::fit_relative_pose (its pose in the first
// sensor's frame), started from --second-init or from localizing the second sensor on its own.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "calib/calibration_solver.hpp"
#include "calib/level_scans.hpp"
#include "calib/relative_pose.hpp"
#include "calib/truth_comparison.hpp"
#include "io/input_error.hpp"
#include "io/open_capture.hpp"
#include "io/scan_source.hpp"
#include "io/velodyne_packet.hpp"
#include "io/veloview_calibration.hpp"
#include "localizer/conic/pose.hpp"
#include "localizer/filter/free_space.hpp"
#include "run/localize_run.hpp"
#include "sensor/builtin_calibration.hpp"
#include "tools/commands.hpp"
#include "tools/json_writer.hpp"
#include "tools/map_options.hpp"
#include "tools/number_list.hpp"
#include "tools/sensor_option.hpp"

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
  std::string sensor;         ///< "[ADDR:]PORT" of the sensor calibrated ("": port 2368)
  std::string second_sensor;  ///< "[ADDR:]PORT" of a second sensor ("": none)
  std::string second_calibration_xml;
  std::string second_init_text;  ///< "x,y,z,roll_deg,pitch_deg,yaw_deg" in the first's frame
  double second_height_m = -1.0;  ///< for its own global start (< 0: --height)
  int settle_scans = 10;     ///< scans left to the filter before any is used
  int max_scans = 60;        ///< scans used, spread evenly over the rest
  double max_climb_mps = 0.02;  ///< scans whose floor rises or falls faster are not used
  int return_stride = 1;     ///< every n-th return of a ring
  double min_range_m = 0.5;  ///< nearer returns are left out (blind zone, the carrier)
  io::MapLoadOptions map_options;
  localizer::LocalizerConfig localizer;
  calib::CalibrationConfig calibration;
};

struct LocalizedScan {
  double utc_s = 0.0;
  localizer::Pose3 T_map_sensor;
};

// The floor under a sensor: the walkable surface of the cell it stands over (a storey's rooms
// may stand at different heights: FJK-Haus has one 8 cm above its storey's floor, and the
// mounting height is measured from the floor under the carrier), else the highest storey floor
// at or below it.
double floor_under(const localizer::FreeSpace& free_space, const maps::PlaneMap& map,
                   const Eigen::Vector3d& sensor) {
  if (const int cell = free_space.cell_at(sensor.x(), sensor.y(), sensor.z()); cell >= 0) {
    return free_space.floor_z_at(cell, sensor.x(), sensor.y(), sensor.z());
  }
  double floor = map.storeys.empty() ? map.bounds.min().z() : map.storeys.front().floor_z;
  for (const auto& storey : map.storeys) {
    if (storey.floor_z <= sensor.z()) floor = std::max(floor, storey.floor_z);
  }
  return floor;
}

// A chosen scan's span: the returns fired at UTC t within (end − interval, end] are its own,
// at τ = t − end from its reference time.
struct ScanWindow {
  double utc_end_s = 0.0;
  double interval_s = 0.0;
};

struct Observations {
  std::vector<calib::Return> returns;
  std::vector<calib::ScanPose> poses;
  std::vector<ScanWindow> windows;  ///< one per pose
  calib::Mounting mounting;
  std::size_t climbing_scans = 0;  ///< after the settling, left out (calib/level_scans.hpp)
};

io::ScanSourceOptions source_options(const CalibrateOptions& o, const io::StreamConfig& stream) {
  io::ScanSourceOptions options;
  options.capture.topic = o.topic;
  options.capture.ports = {stream.data_port, stream.position_port};
  options.stream = stream;
  return options;
}

// Re-reads the capture and gathers the returns of the chosen scans, matched to their localized
// poses by time, each with its firing time from the scan's end (the de-skew the fit refines).
Observations gather(const CalibrateOptions& o, const maps::PlaneMap& map,
                    const sensor::LaserCalibration& calibration, const io::StreamConfig& stream,
                    const std::vector<LocalizedScan>& localized) {
  Observations out;
  if (localized.size() < 2 + static_cast<std::size_t>(o.settle_scans)) {
    throw CLI::ValidationError("--pcap", "only " + std::to_string(localized.size()) +
                                             " scans localized; calibration needs more than " +
                                             std::to_string(o.settle_scans + 1));
  }
  const localizer::FreeSpace free_space(map);
  std::vector<double> times_s, floors_m;
  for (const auto& scan : localized) {
    times_s.push_back(scan.utc_s);
    floors_m.push_back(floor_under(free_space, map, scan.T_map_sensor.translation()));
  }
  const calib::LevelScanChoice level =
      calib::choose_level_scans(times_s, floors_m, static_cast<std::size_t>(o.settle_scans) + 1,
                                static_cast<std::size_t>(o.max_scans), o.max_climb_mps);
  const std::vector<std::size_t>& chosen = level.chosen;
  out.climbing_scans = level.climbing;
  if (chosen.empty()) {
    throw io::InputError(
        o.pcap_path, "scans",
        "every localized scan after the settling climbs (" + std::to_string(level.climbing) +
            " scans: stairs, a ramp, a step); calibration needs scans on a level floor");
  }

  const auto source = io::open_scan_source(o.pcap_path, calibration, source_options(o, stream));
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
    const int scan_index = static_cast<int>(out.poses.size());
    out.windows.push_back({target.utc_s, interval_s});
    const Eigen::Vector3d t = target.T_map_sensor.translation();
    const double floor_z = floors_m[chosen[next]];
    out.poses.push_back(calib::scan_pose_between(previous.T_map_sensor, target.T_map_sensor,
                                                 interval_s, floor_z));
    height_sum += t.z() - floor_z;
    // R = Rz(yaw)·Ry(pitch)·Rx(roll): the pitch and roll the localizer gave, mean over scans.
    const auto angles = localizer::roll_pitch_yaw(target.T_map_sensor.linear());
    pitch_sum += angles.pitch;
    roll_sum += angles.roll;
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
        r.time_s = ret.time_s - scan->end_time_s;
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

// The second sensor: which it is, its calibration, and what was found of it.
struct SecondSensor {
  io::StreamConfig stream;
  sensor::LaserCalibration calibration;
  Eigen::Isometry3d initial = Eigen::Isometry3d::Identity();  ///< T_first_second to start from
  std::string start;  ///< "--second-init" or "localized on its own (…)"
  calib::RelativePoseEstimate estimate;
};

// The second sensor's returns fired within the chosen scans of the first, each with its time
// from that scan's reference (the first sensor's fitted motion carries it). Times meet on the
// capture's UTC clock.
std::vector<calib::Return> gather_second(const CalibrateOptions& o,
                                         const SecondSensor& second,
                                         const std::vector<ScanWindow>& windows) {
  std::vector<calib::Return> returns;
  const auto source =
      io::open_scan_source(o.pcap_path, second.calibration, source_options(o, second.stream));
  while (const auto scan = source->next()) {
    const double offset_s = source->utc_offset_s().value_or(0.0);
    if (scan->end_time_s + offset_s <= windows.front().utc_end_s - windows.front().interval_s)
      continue;
    if (scan->start_time_s + offset_s > windows.back().utc_end_s) break;
    for (const auto& ring : scan->rings) {
      int seen = 0;
      for (const auto& ret : ring.returns) {
        if (ret.status != sensor::ReturnStatus::Valid || ret.range_m < o.min_range_m) continue;
        if (seen++ % o.return_stride != 0) continue;
        const double utc_s = ret.time_s + offset_s;
        const auto window = std::lower_bound(
            windows.begin(), windows.end(), utc_s,
            [](const ScanWindow& w, double t) { return w.utc_end_s < t; });
        if (window == windows.end() || utc_s <= window->utc_end_s - window->interval_s) continue;
        calib::Return r;
        r.laser = ring.channel;
        r.scan = static_cast<int>(window - windows.begin());
        r.azimuth_rad = ret.azimuth_rad;
        r.range_m = ret.range_m;
        r.time_s = utc_s - window->utc_end_s;
        returns.push_back(r);
      }
    }
  }
  if (returns.empty()) {
    throw io::InputError(o.pcap_path, "--second-sensor " + sensor_text(second.stream),
                         "no return of the second sensor within the scans used");
  }
  return returns;
}

// Where the second sensor sits, roughly, from localizing it on its own (global start): its pose
// against the first's at each scan it tracks, T_fs = T_map_first⁻¹·T_map_second, the median
// translation and the mean rotation of the scans within 0.2 m of it. Fit to the planes after.
Eigen::Isometry3d locate_second(const maps::PlaneMap& map, run::LocalizeRunConfig run,
                                const CalibrateOptions& o, const SecondSensor& second,
                                const std::vector<LocalizedScan>& first, std::string& start) {
  std::vector<io::StampedPose> first_poses;
  for (const auto& scan : first) first_poses.push_back({scan.utc_s, scan.T_map_sensor});
  run.stream = second.stream;
  run.calibration = second.calibration;
  run.start = {};
  run.start.global = true;
  run.localizer.motion.height_above_floor_m = o.second_height_m >= 0.0 ? o.second_height_m : o.height_m;
  std::vector<Eigen::Isometry3d> relative;
  std::size_t scans = 0;
  run::run_localization(map, run, [&](double utc_s, const localizer::UpdateResult& r) {
    if (++scans <= static_cast<std::size_t>(o.settle_scans)) return;
    if (r.status != localizer::LocalizerStatus::Tracking) return;
    if (const auto T_map_first = run::odometry_at(first_poses, utc_s)) {
      relative.push_back(T_map_first->inverse() * r.pose);
    }
  });
  if (relative.empty()) {
    throw io::InputError(o.pcap_path, "--second-sensor " + sensor_text(second.stream),
                         "the second sensor was not localized on its own (" +
                             std::to_string(scans) +
                             " scans, none tracked); give its pose with --second-init");
  }
  Eigen::Vector3d median;
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<double> values;
    for (const auto& T : relative) values.push_back(T.translation()(axis));
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    median(axis) = values[values.size() / 2];
  }
  constexpr double kAgreeM = 0.2;
  Eigen::Vector3d t_sum = Eigen::Vector3d::Zero();
  Eigen::Vector4d q_sum = Eigen::Vector4d::Zero();
  int kept = 0;
  for (const auto& T : relative) {
    if ((T.translation() - median).norm() > kAgreeM) continue;
    Eigen::Vector4d q = Eigen::Quaterniond(T.linear()).coeffs();
    if (kept > 0 && q.dot(q_sum) < 0.0) q = -q;  // one hemisphere: q and −q are one rotation
    q_sum += q;
    t_sum += T.translation();
    ++kept;
  }
  if (kept == 0) {
    throw io::InputError(o.pcap_path, "--second-sensor " + sensor_text(second.stream),
                         "the second sensor's poses against the first disagree (none of " +
                             std::to_string(relative.size()) +
                             " tracked scans within 0.2 m of their median); give its pose with "
                             "--second-init");
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(q_sum.normalized()).toRotationMatrix();
  T.translation() = t_sum / kept;
  start = "localized on its own (" + std::to_string(kept) + " of " +
          std::to_string(relative.size()) + " tracked scans agree)";
  return T;
}

void write_second_sensor(JsonWriter& j, const SecondSensor& second) {
  const calib::RelativePoseEstimate& e = second.estimate;
  const auto angles = localizer::roll_pitch_yaw(e.T_first_second.linear());
  const Eigen::Vector3d t = e.T_first_second.translation();
  const std::array<double, 6> value = {t.x(), t.y(), t.z(), angles.roll * kDeg,
                                       angles.pitch * kDeg, angles.yaw * kDeg};
  constexpr std::array<const char*, 6> kNames = {"x_m", "y_m", "z_m",
                                                 "roll_deg", "pitch_deg", "yaw_deg"};
  constexpr std::array<const char*, 6> kSigmaNames = {
      "x_sigma_m", "y_sigma_m", "z_sigma_m", "roll_sigma_deg", "pitch_sigma_deg", "yaw_sigma_deg"};
  j.key("second_sensor").begin_object();
  j.key("sensor").value(sensor_text(second.stream));
  j.key("start").value(second.start);
  j.key("frame").value(
      "pose of the second sensor in the first sensor's frame: p_first = R p_second + t, "
      "R = Rz(yaw) Ry(pitch) Rx(roll)");
  for (int i = 0; i < 6; ++i) {
    const double scale = i < 3 ? 1.0 : kDeg;
    j.key(kNames[i]);
    e.observable[i] ? j.value(value[i]) : j.null();
    j.key(kSigmaNames[i]);
    e.observable[i] ? j.value(std::sqrt(e.covariance(i, i)) * scale) : j.null();
  }
  j.key("observable").value(e.all_observable());
  if (!e.all_observable()) j.key("missing").value(e.missing);
  // Over (x, y, z, roll, pitch, yaw): metres and radians, row-major.
  j.key("covariance").begin_array();
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) j.value(e.covariance(r, c));
  }
  j.end_array();
  j.key("returns").value(static_cast<unsigned long>(e.returns));
  j.key("planes").value(e.planes);
  j.key("rms_m").value(e.rms_m);
  j.key("sigma_m").value(e.sigma_m);
  j.key("iterations").value(e.iterations);
  j.key("converged").value(e.converged);
  j.end_object();
}

void write_report(const std::string& path, const CalibrateOptions& o, const maps::PlaneMap& map,
                  const sensor::LaserCalibration& decode, const calib::CalibrationResult& result,
                  std::size_t climbing_scans, const std::optional<calib::TruthErrors>& truth,
                  const std::optional<SecondSensor>& second) {
  constexpr std::array<const char*, 4> kNames = {"elevation_deg", "vertical_offset_m",
                                                 "azimuth_offset_deg", "range_offset_m"};
  constexpr std::array<double, 4> kScale = {kDeg, 1.0, kDeg, 1.0};
  std::ofstream out(path);
  JsonWriter j(out);
  j.begin_object();
  j.key("tool").value("conicloc calibrate");
  j.key("map").value(o.map_path);
  j.key("pcap").value(o.pcap_path);
  io::StreamConfig stream;
  if (!o.sensor.empty()) apply_sensor_option(o.sensor, "--sensor", stream);
  j.key("sensor").value(sensor_text(stream));
  j.key("decode_calibration").value(o.calibration_xml.empty() ? "built-in" : o.calibration_xml);
  j.key("scans").value(static_cast<int>(result.poses.size()));
  j.key("climbing_scans").value(static_cast<unsigned long>(climbing_scans));
  j.key("returns").value(static_cast<unsigned long>(result.returns));
  j.key("unmapped_returns").value(static_cast<unsigned long>(result.unmapped_returns));
  j.key("rms_m").value(result.rms_m);
  j.key("sigma_m").value(result.sigma_m);
  j.key("sigmas").value(
      "the larger of the model's (independent returns) and the sandwich's (the fit's gradient "
      "spread over scan lines)");
  j.key("range_noise_sigma_m").value(result.noise.range_sigma_m);
  j.key("surface_error_sigma_m").value(result.noise.surface_sigma_m);
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
    // The sigma from σ²·H⁻¹, as if every return were independent with the weights' variance
    // (calibration_solver.hpp): beside the sandwich's, how much the returns' correlation along
    // scan lines and the weights' misfit widen it.
    j.key("elevation_model_sigma_deg");
    e.observability.observable[0] ? j.value(e.model_sigma[0] * kScale[0]) : j.null();
    j.key("observable").value(e.observability.all());
    if (!e.observability.all()) j.key("missing").value(e.observability.missing);
    j.key("returns").value(e.returns);
    j.key("planes").value(e.planes);
    j.end_object();
  }
  j.end_array();
  // height_m: above the floor as the fit places it, where a floor polygon is under the carrier
  // (calibration_solver.hpp, FloorHeight); the model's h above the map's floor beside it.
  const calib::FloorHeight& floor = result.height_above_floor;
  j.key("mounting").begin_object();
  j.key("height_m").value(floor.height_m);
  j.key("height_sigma_m").value(floor.sigma_m);
  j.key("height_floor_scans").value(floor.scans);
  j.key("height_above_map_floor_m").value(result.mounting.height_m);
  j.key("height_above_map_floor_sigma_m").value(result.mounting_sigma[0]);
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
  if (second) write_second_sensor(j, *second);
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
  if (!o.sensor.empty()) apply_sensor_option(o.sensor, "--sensor", run.stream);
  run.localizer = o.localizer;
  run.localizer.motion.height_above_floor_m = o.height_m;
  run.two_sided_walls = loaded.report.two_sided_faces > 0;
  std::optional<SecondSensor> second;
  if (!o.second_sensor.empty()) {
    second.emplace();
    apply_sensor_option(o.second_sensor, "--second-sensor", second->stream);
    if (second->stream.data_port == run.stream.data_port &&
        (second->stream.source_address == 0 || run.stream.source_address == 0 ||
         second->stream.source_address == run.stream.source_address)) {
      throw CLI::ValidationError("--second-sensor",
                                 "names the packets of the first sensor too: give another port, "
                                 "or both sensors' addresses (--sensor ADDR:PORT)");
    }
    const std::string format = io::sniff_capture_format(o.pcap_path);
    if (format != "pcap" && format != "pcapng") {
      throw CLI::ValidationError("--second-sensor",
                                 "needs a pcap/pcapng capture of both sensors: " +
                                     (format.empty() ? std::string("this file") : format) +
                                     " holds one sensor per topic");
    }
    if (!o.second_init_text.empty()) {
      const auto v = parse_numbers(o.second_init_text, 6, "--second-init");
      second->initial =
          localizer::make_pose(v[0], v[1], v[2], v[5] / kDeg, v[4] / kDeg, v[3] / kDeg);
      second->start = "--second-init";
    }
    second->calibration = sensor::builtin_calibration(*model);
    if (!o.second_calibration_xml.empty()) {
      auto calibration = io::read_veloview_calibration(o.second_calibration_xml, *model);
      for (const auto& warning : calibration.warnings) spdlog::warn("{}", warning);
      second->calibration = calibration.calibration;
    }
  }
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

  const Observations observations = gather(o, map, run.calibration, run.stream, localized);
  spdlog::info("{} returns of {} scans; start height {:.3f} m, roll {:.2f}°, pitch {:.2f}°",
               observations.returns.size(), observations.poses.size(),
               observations.mounting.height_m, observations.mounting.roll_rad * kDeg,
               observations.mounting.pitch_rad * kDeg);
  if (observations.climbing_scans > 0) {
    spdlog::info(
        "{} scans left out: the floor under the sensor rose or fell through them faster "
        "than {} m/s (stairs, a ramp, a step; the fit holds the carrier on a level floor)",
        observations.climbing_scans, o.max_climb_mps);
  }
  calib::CalibrationConfig config = o.calibration;
  config.threads = o.localizer.threads;
  const calib::CalibrationResult result = calib::calibrate(
      map, run.calibration, observations.returns, observations.mounting, observations.poses, config);
  spdlog::info("{} returns on planes ({} left out beside them: objects the map lacks), residual "
               "rms {:.4f} m, {} iterations{}",
               result.returns, result.unmapped_returns, result.rms_m, result.iterations,
               result.converged ? "" : " (not converged)");
  if (result.noise.range_sigma_m > 0.0 || result.noise.surface_sigma_m > 0.0) {
    spdlog::info(
        "returns weighed by range noise {:.4f} m and surface error {:.4f} m (over the "
        "incidence cosine)",
        result.noise.range_sigma_m, result.noise.surface_sigma_m);
  } else {
    spdlog::info("returns weighed by the incidence cosine (noise not fitted)");
  }
  for (std::size_t k = 0; k < result.lasers.size(); ++k) {
    const auto& e = result.lasers[k];
    if (!e.observability.all()) spdlog::warn("laser {}: {}", k, e.observability.missing);
  }
  if (!result.planes.empty()) {
    spdlog::info("{} map planes adjusted (prior {:.3f} m)", result.planes.size(),
                 o.calibration.map_sigma_m);
  }
  const calib::FloorHeight& floor = result.height_above_floor;
  const std::string above = floor.scans > 0
                                ? "the fitted floor over " + std::to_string(floor.scans) + " scans"
                                : std::string("the map's floor (no floor polygon under the scans)");
  spdlog::info(
      "mounting: height {:.4f} ± {:.4f} m above {} ({:.4f} ± {:.4f} m above the map's "
      "floor), roll {:.3f} ± {:.3f}°, pitch {:.3f} ± {:.3f}°",
      floor.height_m, floor.sigma_m, above, result.mounting.height_m, result.mounting_sigma[0],
      result.mounting.roll_rad * kDeg, result.mounting_sigma[1] * kDeg,
      result.mounting.pitch_rad * kDeg, result.mounting_sigma[2] * kDeg);

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
  if (second) {
    if (o.second_init_text.empty()) {
      second->initial = locate_second(map, run, o, *second, localized, second->start);
    }
    const auto returns = gather_second(o, *second, observations.windows);
    // Localized on its own, its height is the filter's assumption (--second-height): searched.
    constexpr double kHeightSearchM = 1.0;
    second->estimate =
        calib::fit_relative_pose(map, result, second->calibration, returns, second->initial,
                                 o.calibration,
                                 o.second_init_text.empty() ? kHeightSearchM : 0.0);
    const auto& e = second->estimate;
    const auto angles = localizer::roll_pitch_yaw(e.T_first_second.linear());
    const Eigen::Vector3d t = e.T_first_second.translation();
    auto sd = [&](int i) { return std::sqrt(e.covariance(i, i)) * (i < 3 ? 1000.0 : kDeg); };
    spdlog::info("second sensor {} (start: {}): {} returns on {} planes, residual rms {:.4f} m",
                 sensor_text(second->stream), second->start, e.returns, e.planes, e.rms_m);
    spdlog::info(
        "second sensor in the first's frame: x {:.4f} ± {:.1f} mm, y {:.4f} ± {:.1f} mm, z {:.4f} "
        "± {:.1f} mm, roll {:.3f} ± {:.3f}°, pitch {:.3f} ± {:.3f}°, yaw {:.3f} ± {:.3f}°",
        t.x(), sd(0), t.y(), sd(1), t.z(), sd(2), angles.roll * kDeg, sd(3), angles.pitch * kDeg,
        sd(4), angles.yaw * kDeg, sd(5));
    if (!e.all_observable()) spdlog::warn("second sensor: {}", e.missing);
  }
  if (!o.report_path.empty()) {
    write_report(o.report_path, o, map, run.calibration, result, observations.climbing_scans, truth,
                 second);
  }
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
  cmd->add_option("--scans", o->max_scans, "Scans used, spread over the capture's level ones")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--max-climb", o->max_climb_mps,
                  "Leave out scans whose floor under the sensor rises or falls faster than this "
                  "(m/s: stairs, ramps, steps; the fit holds the carrier on a level floor)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--return-stride", o->return_stride, "Use every n-th return of a ring")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--map-sigma", o->calibration.map_sigma_m,
                  "How far the map's planes may stand off (m): each plane seen is adjusted with "
                  "this prior (0: planes fixed)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--edge-margin", o->calibration.edge_margin_m,
                  "Use a return only where its ray meets the surface this far inside its edges "
                  "(m; near an edge, which returns stay on a surface depends on the range noise)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--unmapped-sigmas", o->calibration.unmapped_objects.median_sigmas,
                  "Leave out returns whose neighbours on the scan line stand off their surface "
                  "together by more than this many std. devs. of their median (objects the map "
                  "lacks: a box by a wall); 0 keeps them")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--noise-bins", o->calibration.return_noise.bins,
                  "Weigh each return by its range residual's variance, range noise plus surface "
                  "error over the incidence cosine squared, both fitted in this many bins of "
                  "returns (0: by the cosine alone, as if the surfaces' error were all)")
      ->check(CLI::Validator(
          [](const std::string& text) {
            try {
              if (text == "0" || std::stoi(text) >= 2) return std::string();
            } catch (const std::exception&) {
            }
            return std::string("0, or 2 bins or more");
          },
          "0 or >= 2"))
      ->capture_default_str();
  cmd->add_option("--sensor", o->sensor,
                  "The sensor to calibrate in a capture of several: [ADDR:]PORT of its data "
                  "packets (default: port 2368, any sender)");
  auto* second = cmd->add_option("--second-sensor", o->second_sensor,
                                 "A second sensor in the capture (pcap), [ADDR:]PORT: estimate "
                                 "its pose in the first sensor's frame (report: second_sensor)");
  cmd->add_option("--second-calibration", o->second_calibration_xml,
                  "The second sensor's calibration (default: built-in)")
      ->check(CLI::ExistingFile)
      ->needs(second);
  cmd->add_option("--second-init", o->second_init_text,
                  "Its pose in the first's frame to start from, x,y,z,roll_deg,pitch_deg,yaw_deg "
                  "(default: localize it on its own, global start)")
      ->needs(second);
  cmd->add_option("--second-height", o->second_height_m,
                  "Its height above the floor for that global start (m; default: --height)")
      ->needs(second);
  cmd->add_option("--threads", o->localizer.threads,
                  "Threads of the localizer and the solver (0: all cores; same result for any)")
      ->capture_default_str();
  cmd->add_option("--seed", o->localizer.seed, "Localizer random seed")->capture_default_str();
  cmd->callback([o] { run_calibrate(*o); });
}

}  // namespace conicloc::tools
