// `conicloc predict --pose x,y,z,yaw_deg[,pitch_deg,roll_deg]`: the scan the conic sensor model
// predicts for a VLP-16 at a pose in a map, in the columns of `conicloc decode`, and optionally
// the per-(ring, polygon) conics with their type, eccentricity, coefficients and arcs.
#include <spdlog/spdlog.h>

#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>

#include "io/indoorgml.hpp"
#include "io/input_error.hpp"
#include "localizer/conic/conic_scan_predictor.hpp"
#include "localizer/conic/plane_culling.hpp"
#include "localizer/conic/polygon_arcs.hpp"
#include "localizer/conic/pose.hpp"
#include "localizer/conic/projective_conic.hpp"
#include "maps/plane_index.hpp"
#include "sensor/builtin_calibration.hpp"
#include "tools/commands.hpp"
#include "tools/map_options.hpp"
#include "tools/point_csv.hpp"

namespace conicloc::tools {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr double kRadToDeg = 180.0 / std::numbers::pi;

struct PredictOptions {
  std::string map_path = example_map_path();
  std::string pose;
  double azimuth_step_deg = 0.2;
  double min_range_m = 0.3;
  double max_range_m = 100.0;
  std::string csv_path;
  std::string conics_path;
  io::MapLoadOptions map_options;
};

localizer::Pose3 parse_pose(const std::string& text) {
  std::vector<double> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    std::size_t used = 0;
    double value = 0.0;
    try {
      value = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() || !std::isfinite(value)) {
      throw std::invalid_argument("--pose: '" + item + "' is not a finite number (in '" + text +
                                  "')");
    }
    values.push_back(value);
  }
  if (values.size() != 4 && values.size() != 6) {
    throw std::invalid_argument("--pose: expected x,y,z,yaw_deg[,pitch_deg,roll_deg], got '" +
                                text + "'");
  }
  const double pitch = values.size() == 6 ? values[4] : 0.0;
  const double roll = values.size() == 6 ? values[5] : 0.0;
  return localizer::make_pose(values[0], values[1], values[2], values[3] * kDegToRad,
                              pitch * kDegToRad, roll * kDegToRad);
}

std::ofstream open_output(const std::string& path) {
  std::ofstream out(path);
  if (!out) throw io::InputError(path, "", "cannot write file");
  return out;
}

void write_scan_csv(const std::string& path, const localizer::ConicScanPredictor& predictor,
                    const localizer::PredictedScan& predicted, double step_rad) {
  std::ofstream csv = open_output(path);
  csv << kPointCsvHeader;
  std::vector<double> azimuths;
  for (int i = 0; i * step_rad < 2.0 * std::numbers::pi - 1e-12; ++i)
    azimuths.push_back(i * step_rad);
  std::vector<double> ranges(azimuths.size());
  std::size_t rows = 0;
  for (const auto& ring : predictor.rings()) {
    predicted.ring(ring.ring).evaluate_sorted(azimuths, ranges);
    for (std::size_t i = 0; i < azimuths.size(); ++i) {
      if (!std::isfinite(ranges[i])) continue;
      const Eigen::Vector3d p = ring.point(azimuths[i], ranges[i]);
      csv << fmt::format("0,{},{:.4f},{:.3f},0,0.000000,{:.4f},{:.4f},{:.4f},strongest\n",
                         ring.ring, azimuths[i] * kRadToDeg, ranges[i], p.x(), p.y(), p.z());
      ++rows;
    }
  }
  spdlog::info("wrote {} predicted returns to {}", rows, path);
}

std::string arcs_text(const std::vector<std::pair<double, double>>& arcs) {
  std::string text;
  for (const auto& [begin, end] : arcs) {
    text +=
        fmt::format("{}{:.4f}:{:.4f}", text.empty() ? "" : ";", begin * kRadToDeg, end * kRadToDeg);
  }
  return text;
}

void write_conics_csv(const std::string& path, const maps::PlaneMap& map,
                      const localizer::ConicScanPredictor& predictor, const localizer::Pose3& pose,
                      const std::vector<int>& candidates,
                      const localizer::PredictedScan& predicted) {
  std::ofstream csv = open_output(path);
  csv << "ring,elevation_deg,polygon,source_id,type,eccentricity,A,B,C,E,"
         "C00,C01,C02,C10,C11,C12,C20,C21,C22,arcs_deg,visible_arcs_deg\n";
  localizer::PredictionWorkspace workspace;
  for (const int index : candidates) {
    localizer::add_sensor_polygon(map.polygons[index], index, pose, workspace);
  }
  std::size_t rows = 0;
  for (const auto& ring : predictor.rings()) {
    // Visible (after occlusion) arcs per polygon, from the predicted scan line.
    std::map<int, std::vector<std::pair<double, double>>> visible;
    const auto& line = predicted.ring(ring.ring);
    for (std::size_t i = 0; i < line.piece_count(); ++i) {
      if (line.polygon[i] >= 0)
        visible[line.polygon[i]].emplace_back(line.boundary_rad[i], line.boundary_rad[i + 1]);
    }
    for (const auto& polygon : workspace.polygons) {
      std::vector<localizer::PredictionWorkspace::Arc> arcs;
      localizer::append_polygon_arcs(ring, polygon, map.polygons[polygon.polygon], workspace, arcs);
      if (arcs.empty()) continue;
      std::vector<std::pair<double, double>> clipped;
      for (const auto& arc : arcs) clipped.emplace_back(arc.begin_rad, arc.end_rad);
      const localizer::SensorPlane plane = localizer::sensor_plane(polygon);
      const localizer::RingConic ray = localizer::ring_conic(ring, plane);
      const localizer::ProjectiveConic conic = localizer::projective_conic(ring, plane);
      const Eigen::Matrix3d& C = conic.C;
      csv << fmt::format(
          "{},{:.3f},{},{},{},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},", ring.ring,
          ring.elevation_rad * kRadToDeg, polygon.polygon, map.polygons[polygon.polygon].source_id,
          localizer::conic_type_name(conic.type), conic.eccentricity, ray.A, ray.B, ray.C, ray.E);
      csv << fmt::format("{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{},{}\n",
                         C(0, 0), C(0, 1), C(0, 2), C(1, 0), C(1, 1), C(1, 2), C(2, 0), C(2, 1),
                         C(2, 2), arcs_text(clipped), arcs_text(visible[polygon.polygon]));
      ++rows;
    }
  }
  spdlog::info("wrote {} (ring, polygon) conics to {}", rows, path);
}

void run_predict(const PredictOptions& options) {
  if (!(options.azimuth_step_deg > 0.0) || options.azimuth_step_deg > 360.0) {
    throw std::invalid_argument("--azimuth-step must be in (0, 360] degrees");
  }
  const localizer::Pose3 pose = parse_pose(options.pose);
  const maps::PlaneMap map = load_map(options.map_path, options.map_options).map;
  const auto calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  const maps::PlaneIndex index(map);
  const localizer::PlaneCuller culler(map, index, calibration, {}, options.max_range_m);
  const localizer::CullResult culled = culler.cull(pose);
  spdlog::info(
      "{} polygons: {} kept, {} out of range, {} facing away, {} outside the field of view",
      culled.considered, culled.kept.size(), culled.out_of_range, culled.facing_away,
      culled.outside_field_of_view);
  const localizer::ConicScanPredictor predictor(
      map, calibration, {.min_range_m = options.min_range_m}, options.max_range_m);
  localizer::PredictedScan predicted;
  predictor.predict(pose, culled.kept, predicted);
  std::size_t pieces = 0;
  for (const auto& ring : predicted.rings) pieces += ring.piece_count();
  spdlog::info("{} rings, {} scan-line pieces", predicted.rings.size(), pieces);
  if (!options.csv_path.empty()) {
    write_scan_csv(options.csv_path, predictor, predicted, options.azimuth_step_deg * kDegToRad);
  }
  if (!options.conics_path.empty()) {
    write_conics_csv(options.conics_path, map, predictor, pose, culled.kept, predicted);
  }
}

}  // namespace

void add_predict_command(CLI::App& app) {
  auto options = std::make_shared<PredictOptions>();
  auto* cmd = app.add_subcommand(
      "predict",
      "Predict the scan of a VLP-16 at a pose with the projective-conic sensor model.\n"
      "--csv: the columns of `conicloc decode` (scan,ring,azimuth_deg,range_m,intensity,time_s,\n"
      "x,y,z,return; x y z in the sensor frame, scan 0, intensity 0, time 0, return strongest).\n"
      "--conics: one row per (ring, polygon hit): conic type, eccentricity, ray form A,B,C,E\n"
      "(r = E/(A cos θ + B sin θ + C)), the 3x3 projective conic C = Hᵀ Q H, its clipped arcs and\n"
      "the arcs left visible after occlusion (degrees, begin:end;...).");
  cmd->add_option("--map", options->map_path, "IndoorGML map")->check(CLI::ExistingFile);
  add_map_load_options(cmd, options->map_options);
  cmd->add_option("--pose", options->pose,
                  "Sensor pose in the map: x,y,z,yaw_deg[,pitch_deg,roll_deg]")
      ->required();
  cmd->add_option("--azimuth-step", options->azimuth_step_deg, "Azimuth step of --csv (degrees)");
  cmd->add_option("--min-range", options->min_range_m, "Minimum range (m)");
  cmd->add_option("--max-range", options->max_range_m, "Maximum range (m)");
  cmd->add_option("--csv", options->csv_path, "Write the predicted returns (CSV)");
  cmd->add_option("--conics", options->conics_path, "Write the conics per ring and polygon (CSV)");
  cmd->callback([options] { run_predict(*options); });
}

}  // namespace conicloc::tools
