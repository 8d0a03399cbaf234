#include "tools/run_recording.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <sstream>

#include "maps/polygon_triangulation.hpp"
#include "tools/base64.hpp"
#include "tools/foxglove_schemas.hpp"
#include "tools/json_writer.hpp"

namespace conicloc::tools {
namespace {

constexpr const char* kMapFrame = "map";
constexpr const char* kSensorFrame = "sensor";

// /scan point layout: x, y, z, intensity as float32, ring as uint16 (little-endian, packed).
constexpr std::uint32_t kPointStride = 18;

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

void put_le(std::string& bytes, std::uint32_t value, int count) {
  for (int i = 0; i < count; ++i) bytes += static_cast<char>(value >> (8 * i));
}

/// A SceneEntity's fields up to its primitives; the caller writes "lines" and "triangles" and
/// closes the entity with end_entity().
void begin_entity(JsonWriter& json, std::uint64_t time_ns, const char* frame, const char* id) {
  json.begin_object();
  json.key("deletions").begin_array().end_array();
  json.key("entities").begin_array().begin_object();
  json.key("timestamp");
  write_time(json, time_ns);
  json.key("frame_id").value(frame);
  json.key("id").value(id);
  json.key("lifetime").begin_object().key("sec").value(0).key("nsec").value(0).end_object();
  json.key("frame_locked").value(false);
  for (const char* unused :
       {"metadata", "arrows", "cubes", "spheres", "cylinders", "texts", "models"}) {
    json.key(unused).begin_array().end_array();
  }
}

void end_entity(JsonWriter& json) {
  json.end_object().end_array().end_object();
}

void write_primitive_end(JsonWriter& json, const Rgba& colour) {
  json.key("color");
  write_color(json, colour);
  json.key("colors").begin_array().end_array();
  json.key("indices").begin_array().end_array();
  json.end_object();
}

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
  std::ostringstream text;
  JsonWriter json(text);
  begin_entity(json, time_ns, kMapFrame, "map");
  json.key("lines").begin_array().end_array();
  json.key("triangles").begin_array();
  // A triangle list per surface kind, three points per triangle.
  for (const auto kind : {maps::SurfaceKind::Wall, maps::SurfaceKind::Floor,
                          maps::SurfaceKind::Ceiling, maps::SurfaceKind::Slope}) {
    json.begin_object();
    json.key("pose");
    write_pose(json, localizer::Pose3::Identity());
    json.key("points").begin_array();
    for (const maps::PlanarPolygon& polygon : map_.polygons) {
      if (polygon.kind != kind) continue;
      std::vector<Eigen::Vector3d> vertices(polygon.outer.begin(), polygon.outer.end());
      for (const auto& hole : polygon.holes)
        vertices.insert(vertices.end(), hole.begin(), hole.end());
      for (const maps::Triangle& triangle : maps::triangulate(polygon)) {
        for (const int corner : triangle)
          write_point(json, vertices[static_cast<std::size_t>(corner)]);
      }
    }
    json.end_array();
    write_primitive_end(json, colour_of(kind));
  }
  json.end_array();
  end_entity(json);
  return text.str();
}

std::string RunRecording::conics_update(std::uint64_t time_ns,
                                        const localizer::Pose3& T_map_sensor) {
  const localizer::CullResult culled = culler_.cull(T_map_sensor);
  predictor_.predict(T_map_sensor, culled.kept, predicted_);
  std::ostringstream text;
  JsonWriter json(text);
  begin_entity(json, time_ns, kSensorFrame, "conics");
  json.key("triangles").begin_array().end_array();
  json.key("lines").begin_array();
  for (const localizer::RingGeometry& ring : predictor_.rings()) {
    // Each piece of the predicted scan line is one polygon's conic over an azimuth interval:
    // sampled every conic_step_rad (its ends included), split where the range leaves
    // [min, max] (no return).
    const localizer::PredictedRing& line = predicted_.ring(ring.ring);
    for (std::size_t piece = 0; piece < line.piece_count(); ++piece) {
      if (line.polygon[piece] < 0) continue;
      const double begin = line.boundary_rad[piece];
      const double end = std::nextafter(line.boundary_rad[piece + 1], begin);  // still this piece
      const int steps =
          std::max(1, static_cast<int>(std::ceil((end - begin) / options_.conic_step_rad)));
      std::vector<Eigen::Vector3d> strip;
      const auto flush = [&] {
        if (strip.size() >= 2) {
          json.begin_object();
          json.key("type").value(static_cast<int>(LineType::LineStrip));
          json.key("pose");
          write_pose(json, localizer::Pose3::Identity());
          json.key("thickness").value(0.03);
          json.key("scale_invariant").value(false);
          json.key("points").begin_array();
          for (const auto& point : strip) write_point(json, point);
          json.end_array();
          write_primitive_end(json, {1.0, 0.55, 0.0, 1.0});
        }
        strip.clear();
      };
      for (int i = 0; i <= steps; ++i) {
        const double azimuth = begin + (end - begin) * i / steps;
        const double range = line.range(azimuth);
        if (std::isfinite(range)) {
          strip.push_back(ring.point(azimuth, range));
        } else {
          flush();
        }
      }
      flush();
    }
  }
  json.end_array();
  end_entity(json);
  return text.str();
}

void RunRecording::add(double utc_s, const localizer::UpdateResult& result,
                       const sensor::Scan& scan, const localizer::ParticleSet& particles) {
  const std::uint64_t time_ns = to_ns(utc_s);
  if (!map_written_) {
    writer_.write(map_channel_, time_ns, map_update(time_ns));
    map_written_ = true;
  }

  {  // /tf first: a viewer places the frame-"sensor" messages of this time with it
    std::ostringstream text;
    JsonWriter json(text);
    const Eigen::Quaterniond q(result.pose.linear());
    json.begin_object();
    json.key("timestamp");
    write_time(json, time_ns);
    json.key("parent_frame_id").value(kMapFrame);
    json.key("child_frame_id").value(kSensorFrame);
    json.key("translation");
    write_point(json, result.pose.translation());
    json.key("rotation").begin_object();
    json.key("x").value(q.x()).key("y").value(q.y()).key("z").value(q.z()).key("w").value(q.w());
    json.end_object().end_object();
    writer_.write(tf_channel_, time_ns, text.str());
  }
  {
    std::string points;
    for (const sensor::RingScan& ring : scan.rings) {
      for (const sensor::Return& ret : ring.returns) {
        if (ret.status != sensor::ReturnStatus::Valid) continue;
        const Eigen::Vector3d p = sensor::sensor_point(ring, ret);
        for (const double v : {p.x(), p.y(), p.z(), static_cast<double>(ret.intensity)}) {
          put_le(points, std::bit_cast<std::uint32_t>(static_cast<float>(v)), 4);
        }
        put_le(points, static_cast<std::uint32_t>(ring.ring), 2);
      }
    }
    std::ostringstream text;
    JsonWriter json(text);
    json.begin_object();
    json.key("timestamp");
    write_time(json, time_ns);
    json.key("frame_id").value(kSensorFrame);
    json.key("pose");
    write_pose(json, localizer::Pose3::Identity());
    json.key("point_stride").value(static_cast<unsigned long>(kPointStride));
    json.key("fields").begin_array();
    const std::pair<const char*, NumericType> fields[] = {{"x", NumericType::Float32},
                                                          {"y", NumericType::Float32},
                                                          {"z", NumericType::Float32},
                                                          {"intensity", NumericType::Float32},
                                                          {"ring", NumericType::Uint16}};
    int offset = 0;
    for (const auto& [name, type] : fields) {
      json.begin_object().key("name").value(name).key("offset").value(offset);
      json.key("type").value(static_cast<int>(type)).end_object();
      offset += type == NumericType::Float32 ? 4 : 2;
    }
    json.end_array();
    json.key("data").value(
        base64(std::span(reinterpret_cast<const std::uint8_t*>(points.data()), points.size())));
    json.end_object();
    writer_.write(scan_channel_, time_ns, text.str());
  }
  {
    // Every k-th particle, k = ceil(n / max): an even thinning of the cloud, no random draw.
    const std::size_t stride =
        std::max<std::size_t>(1, (particles.size() + options_.max_particles - 1) /
                                     std::max<std::size_t>(1, options_.max_particles));
    std::ostringstream text;
    JsonWriter json(text);
    json.begin_object();
    json.key("timestamp");
    write_time(json, time_ns);
    json.key("frame_id").value(kMapFrame);
    json.key("poses").begin_array();
    for (std::size_t i = 0; i < particles.size(); i += stride) {
      write_pose(json, particles[i].state.to_pose());
    }
    json.end_array().end_object();
    writer_.write(particles_channel_, time_ns, text.str());
  }
  {
    std::ostringstream text;
    JsonWriter json(text);
    json.begin_object();
    json.key("timestamp");
    write_time(json, time_ns);
    json.key("frame_id").value(kMapFrame);
    json.key("pose");
    write_pose(json, result.pose);
    json.end_object();
    writer_.write(estimate_channel_, time_ns, text.str());
  }
  writer_.write(conics_channel_, time_ns, conics_update(time_ns, result.pose));
}

}  // namespace conicloc::tools
