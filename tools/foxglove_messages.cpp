#include "tools/foxglove_messages.hpp"

#include <Eigen/Geometry>
#include <bit>
#include <cmath>
#include <sstream>
#include <utility>

#include "tools/base64.hpp"
#include "tools/json_writer.hpp"

namespace conicloc::tools {
namespace {

// The JSON values of foxglove.NumericType and foxglove.LineType used here.
constexpr int kUint16 = 3;
constexpr int kFloat32 = 7;
constexpr int kLineStrip = 0;

double rounded(double metres) {
  return std::round(metres * 1e4) / 1e4;
}

/// {"sec": ..., "nsec": ...}
void write_time(JsonWriter& json, std::uint64_t time_ns) {
  json.begin_object();
  json.key("sec").value(static_cast<unsigned long>(time_ns / 1'000'000'000U));
  json.key("nsec").value(static_cast<unsigned long>(time_ns % 1'000'000'000U));
  json.end_object();
}

/// foxglove.Vector3 / Point3
void write_point(JsonWriter& json, const Eigen::Vector3d& point) {
  json.begin_object();
  json.key("x").value(rounded(point.x()));
  json.key("y").value(rounded(point.y()));
  json.key("z").value(rounded(point.z()));
  json.end_object();
}

void write_quaternion(JsonWriter& json, const localizer::Pose3& pose) {
  const Eigen::Quaterniond q(pose.linear());
  json.begin_object();
  json.key("x").value(q.x()).key("y").value(q.y()).key("z").value(q.z()).key("w").value(q.w());
  json.end_object();
}

/// foxglove.Pose: {"position": {x, y, z}, "orientation": {x, y, z, w}}
void write_pose(JsonWriter& json, const localizer::Pose3& pose) {
  json.begin_object();
  json.key("position");
  write_point(json, pose.translation());
  json.key("orientation");
  write_quaternion(json, pose);
  json.end_object();
}

void write_points(JsonWriter& json, const std::vector<Eigen::Vector3d>& points) {
  json.key("points").begin_array();
  for (const auto& point : points) write_point(json, point);
  json.end_array();
}

/// The fields every primitive ends with: one colour, no per-point colours, no indices.
void write_colour_and_end(JsonWriter& json, const Rgba& colour) {
  json.key("color").begin_object();
  json.key("r").value(colour.r).key("g").value(colour.g).key("b").value(colour.b);
  json.key("a").value(colour.a).end_object();
  json.key("colors").begin_array().end_array();
  json.key("indices").begin_array().end_array();
  json.end_object();
}

/// The header of a stamped message: {"timestamp": ..., "frame_id": ...
void begin_stamped(JsonWriter& json, std::uint64_t time_ns, const std::string& frame) {
  json.begin_object();
  json.key("timestamp");
  write_time(json, time_ns);
  json.key("frame_id").value(frame);
}

void put_le(std::string& bytes, std::uint32_t value, int count) {
  for (int i = 0; i < count; ++i) bytes += static_cast<char>(value >> (8 * i));
}

}  // namespace

std::string frame_transform_message(std::uint64_t time_ns, const std::string& parent,
                                    const std::string& child,
                                    const localizer::Pose3& T_parent_child) {
  std::ostringstream text;
  JsonWriter json(text);
  json.begin_object();
  json.key("timestamp");
  write_time(json, time_ns);
  json.key("parent_frame_id").value(parent);
  json.key("child_frame_id").value(child);
  json.key("translation");
  write_point(json, T_parent_child.translation());
  json.key("rotation");
  write_quaternion(json, T_parent_child);
  json.end_object();
  return text.str();
}

std::string point_cloud_message(std::uint64_t time_ns, const std::string& frame,
                                const sensor::Scan& scan) {
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
  begin_stamped(json, time_ns, frame);
  json.key("pose");
  write_pose(json, localizer::Pose3::Identity());
  json.key("point_stride").value(static_cast<unsigned long>(kScanPointStride));
  json.key("fields").begin_array();
  const std::pair<const char*, int> fields[] = {{"x", kFloat32},
                                                {"y", kFloat32},
                                                {"z", kFloat32},
                                                {"intensity", kFloat32},
                                                {"ring", kUint16}};
  int offset = 0;
  for (const auto& [name, type] : fields) {
    json.begin_object().key("name").value(name).key("offset").value(offset);
    json.key("type").value(type).end_object();
    offset += type == kFloat32 ? 4 : 2;
  }
  json.end_array();
  json.key("data").value(
      base64(std::span(reinterpret_cast<const std::uint8_t*>(points.data()), points.size())));
  json.end_object();
  return text.str();
}

std::string pose_in_frame_message(std::uint64_t time_ns, const std::string& frame,
                                  const localizer::Pose3& pose) {
  std::ostringstream text;
  JsonWriter json(text);
  begin_stamped(json, time_ns, frame);
  json.key("pose");
  write_pose(json, pose);
  json.end_object();
  return text.str();
}

std::string poses_in_frame_message(std::uint64_t time_ns, const std::string& frame,
                                   const std::vector<localizer::Pose3>& poses) {
  std::ostringstream text;
  JsonWriter json(text);
  begin_stamped(json, time_ns, frame);
  json.key("poses").begin_array();
  for (const auto& pose : poses) write_pose(json, pose);
  json.end_array().end_object();
  return text.str();
}

std::string scene_update_message(std::uint64_t time_ns, const std::string& frame,
                                 const std::string& id, const std::vector<LineStrip>& lines,
                                 const std::vector<TriangleList>& triangles) {
  std::ostringstream text;
  JsonWriter json(text);
  json.begin_object();
  json.key("deletions").begin_array().end_array();
  json.key("entities").begin_array();
  begin_stamped(json, time_ns, frame);
  json.key("id").value(id);
  json.key("lifetime").begin_object().key("sec").value(0).key("nsec").value(0).end_object();
  json.key("frame_locked").value(false);
  // Every primitive list, the unused ones empty (a viewer may expect each of them).
  for (const char* unused :
       {"metadata", "arrows", "cubes", "spheres", "cylinders", "texts", "models"}) {
    json.key(unused).begin_array().end_array();
  }
  json.key("lines").begin_array();
  for (const LineStrip& line : lines) {
    json.begin_object();
    json.key("type").value(kLineStrip);
    json.key("pose");
    write_pose(json, localizer::Pose3::Identity());
    json.key("thickness").value(line.thickness_m);
    json.key("scale_invariant").value(false);
    write_points(json, line.points);
    write_colour_and_end(json, line.colour);
  }
  json.end_array();
  json.key("triangles").begin_array();
  for (const TriangleList& list : triangles) {
    json.begin_object();
    json.key("pose");
    write_pose(json, localizer::Pose3::Identity());
    write_points(json, list.points);
    write_colour_and_end(json, list.colour);
  }
  json.end_array();
  json.end_object().end_array().end_object();
  return text.str();
}

}  // namespace conicloc::tools
