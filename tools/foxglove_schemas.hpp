#pragma once
// The JSON schemas ("jsonschema" schema encoding) of the Foxglove message types a recording uses,
// and the JSON writing of their shared parts (time, pose, colour). Field names and enum values
// are Foxglove's (docs.foxglove.dev, "Message schemas"); a schema lists the fields the recording
// writes. Foxglove and Lichtblick recognise a message type by its schema name
// (foxglove.PointCloud, ...), and decode a JSON "bytes" field from base64 where its schema says
// "contentEncoding": "base64".

#include <cstdint>
#include <string>

#include "localizer/pose.hpp"
#include "tools/json_writer.hpp"

namespace conicloc::tools {

std::string scene_update_schema();     ///< foxglove.SceneUpdate
std::string point_cloud_schema();      ///< foxglove.PointCloud
std::string poses_in_frame_schema();   ///< foxglove.PosesInFrame
std::string pose_in_frame_schema();    ///< foxglove.PoseInFrame
std::string frame_transform_schema();  ///< foxglove.FrameTransform

/// foxglove.NumericType and foxglove.LinePrimitive's type, as their JSON values.
enum class NumericType : int { Uint16 = 3, Float32 = 7 };
enum class LineType : int { LineStrip = 0, LineLoop = 1, LineList = 2 };

struct Rgba {
  double r = 1.0, g = 1.0, b = 1.0, a = 1.0;
};

/// {"sec": ..., "nsec": ...}
void write_time(JsonWriter& json, std::uint64_t time_ns);
/// foxglove.Pose: {"position": {x, y, z}, "orientation": {x, y, z, w}}
void write_pose(JsonWriter& json, const localizer::Pose3& pose);
/// foxglove.Vector3 / Point3 rounded to 0.1 mm (shorter JSON; far below the sensor's noise).
void write_point(JsonWriter& json, const Eigen::Vector3d& point);
void write_color(JsonWriter& json, const Rgba& colour);

}  // namespace conicloc::tools
