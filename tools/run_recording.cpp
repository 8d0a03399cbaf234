#include "tools/run_recording.hpp"

#include <algorithm>
#include <cmath>

#include "maps/polygon_triangulation.hpp"
#include "tools/foxglove_messages.hpp"
#include "tools/foxglove_schemas.hpp"

namespace conicloc::tools {
namespace {

const std::string kMapFrame = "map";
const std::string kSensorFrame = "sensor";

std::uint64_t to_ns(double utc_s) {
  return static_cast<std::uint64_t>(std::llround(std::max(0.0, utc_s) * 1e9));
}

// Surface colours as in the OBJ export's materials; ceilings nearly clear and walls half clear
// so that the view from above reaches the scan inside the rooms.
Rgba colour_of(maps::SurfaceKind kind) {
  switch (kind) {
    case maps::SurfaceKind::Wall:
      return {0.80, 0.78, 0.74, 0.5};
    case maps::SurfaceKind::Floor:
      return {0.62, 0.55, 0.45, 1.0};
    case maps::SurfaceKind::Ceiling:
      return {0.90, 0.90, 0.92, 0.1};
    case maps::SurfaceKind::Slope:
      return {0.70, 0.55, 0.35, 0.8};
  }
  return {};
}

constexpr Rgba kConicColour = {1.0, 0.55, 0.0, 1.0};

localizer::CullConfig cull_config(const RecordingOptions& options) {
  localizer::CullConfig config;
  config.cull_back_faces = options.cull_back_faces;
  return config;
}

}  // namespace

RunRecording::RunRecording(const std::string& path, const maps::PlaneMap& map,
                           const sensor::LaserCalibration& calibration, RecordingOptions options)
    : map_(map),
      options_(options),
      writer_(path),
      index_(map),
      culler_(map, index_, calibration, cull_config(options)),
      predictor_(map, calibration) {
  const auto channel = [&](const char* topic, const char* schema_name, const std::string& schema) {
    return writer_.add_channel(writer_.add_schema(schema_name, "jsonschema", schema), topic,
                               "json");
  };
  // One schema per type: /map and /conics share foxglove.SceneUpdate.
  const std::uint16_t scene =
      writer_.add_schema("foxglove.SceneUpdate", "jsonschema", scene_update_schema());
  map_channel_ = writer_.add_channel(scene, "/map", "json");
  scan_channel_ = channel("/scan", "foxglove.PointCloud", point_cloud_schema());
  particles_channel_ = channel("/particles", "foxglove.PosesInFrame", poses_in_frame_schema());
  estimate_channel_ = channel("/estimate", "foxglove.PoseInFrame", pose_in_frame_schema());
  conics_channel_ = writer_.add_channel(scene, "/conics", "json");
  tf_channel_ = channel("/tf", "foxglove.FrameTransform", frame_transform_schema());
}

std::string RunRecording::map_update(std::uint64_t time_ns) const {
  // A triangle list per surface kind; each polygon's triangles index its outer ring, then holes.
  std::vector<TriangleList> lists;
  for (const auto kind : {maps::SurfaceKind::Wall, maps::SurfaceKind::Floor,
                          maps::SurfaceKind::Ceiling, maps::SurfaceKind::Slope}) {
    TriangleList list;
    list.colour = colour_of(kind);
    for (const maps::PlanarPolygon& polygon : map_.polygons) {
      if (polygon.kind != kind) continue;
      std::vector<Eigen::Vector3d> vertices(polygon.outer.begin(), polygon.outer.end());
      for (const auto& hole : polygon.holes) {
        vertices.insert(vertices.end(), hole.begin(), hole.end());
      }
      for (const maps::Triangle& triangle : maps::triangulate(polygon)) {
        for (const int corner : triangle) {
          list.points.push_back(vertices[static_cast<std::size_t>(corner)]);
        }
      }
    }
    if (!list.points.empty()) lists.push_back(std::move(list));
  }
  return scene_update_message(time_ns, kMapFrame, "map", {}, lists);
}

std::string RunRecording::conics_update(std::uint64_t time_ns,
                                        const localizer::Pose3& T_map_sensor) {
  const localizer::CullResult culled = culler_.cull(T_map_sensor);
  predictor_.predict(T_map_sensor, culled.kept, predicted_);
  std::vector<LineStrip> lines;
  LineStrip strip;
  strip.colour = kConicColour;
  const auto flush = [&] {
    if (strip.points.size() >= 2) lines.push_back(strip);
    strip.points.clear();
  };
  for (const localizer::RingGeometry& ring : predictor_.rings()) {
    // Each piece of the predicted scan line is one polygon's conic over an azimuth interval:
    // sampled every conic_step_rad, its ends included, and split where the range leaves
    // [min, max] (no return).
    const localizer::PredictedRing& line = predicted_.ring(ring.ring);
    for (std::size_t piece = 0; piece < line.piece_count(); ++piece) {
      if (line.polygon[piece] < 0) continue;
      const double begin = line.boundary_rad[piece];
      const double end = std::nextafter(line.boundary_rad[piece + 1], begin);  // still this piece
      const int steps =
          std::max(1, static_cast<int>(std::ceil((end - begin) / options_.conic_step_rad)));
      for (int i = 0; i <= steps; ++i) {
        const double azimuth = begin + (end - begin) * i / steps;
        const double range = line.range(azimuth);
        if (std::isfinite(range)) {
          strip.points.push_back(ring.point(azimuth, range));
        } else {
          flush();
        }
      }
      flush();
    }
  }
  return scene_update_message(time_ns, kSensorFrame, "conics", lines, {});
}

void RunRecording::add(double utc_s, const localizer::UpdateResult& result,
                       const sensor::Scan& scan, const localizer::ParticleSet& particles) {
  const std::uint64_t time_ns = to_ns(utc_s);
  if (!map_written_) {
    writer_.write(map_channel_, time_ns, map_update(time_ns));
    map_written_ = true;
  }
  // /tf first: a viewer places this time's frame-"sensor" messages with it.
  writer_.write(tf_channel_, time_ns,
                frame_transform_message(time_ns, kMapFrame, kSensorFrame, result.pose));
  writer_.write(scan_channel_, time_ns, point_cloud_message(time_ns, kSensorFrame, scan));

  // Every k-th particle, k = ceil(n / max): an even thinning of the cloud, no random draw.
  const std::size_t most = std::max<std::size_t>(1, options_.max_particles);
  const std::size_t stride = std::max<std::size_t>(1, (particles.size() + most - 1) / most);
  std::vector<localizer::Pose3> poses;
  for (std::size_t i = 0; i < particles.size(); i += stride) {
    poses.push_back(particles[i].state.to_pose());
  }
  writer_.write(particles_channel_, time_ns, poses_in_frame_message(time_ns, kMapFrame, poses));
  writer_.write(estimate_channel_, time_ns, pose_in_frame_message(time_ns, kMapFrame, result.pose));
  writer_.write(conics_channel_, time_ns, conics_update(time_ns, result.pose));
}

}  // namespace conicloc::tools
