#pragma once
// Foxglove messages as JSON text (the "json" message encoding; schemas in
// tools/foxglove_schemas.hpp): frame transforms, point clouds, poses and scene updates of line
// strips and triangle lists. Times are nanoseconds since the Unix epoch; positions are rounded to
// 0.1 mm (shorter text, far below a LiDAR's noise).

#include <cstdint>
#include <string>
#include <vector>

#include "localizer/conic/pose.hpp"
#include "sensor/scan.hpp"

namespace conicloc::tools {

struct Rgba {
  double r = 1.0, g = 1.0, b = 1.0, a = 1.0;
};

/// foxglove.LinePrimitive of type LINE_STRIP.
struct LineStrip {
  std::vector<Eigen::Vector3d> points;
  Rgba colour;
  double thickness_m = 0.02;
};

/// foxglove.TriangleListPrimitive: every three points one triangle.
struct TriangleList {
  std::vector<Eigen::Vector3d> points;
  Rgba colour;
};

/// foxglove.FrameTransform from `parent` to `child`: T_parent_child.
std::string frame_transform_message(std::uint64_t time_ns, const std::string& parent,
                                    const std::string& child,
                                    const localizer::Pose3& T_parent_child);

/// foxglove.PointCloud of the valid returns of `scan` in `frame`: x, y, z, intensity as float32
/// and ring as uint16, little-endian, packed (point_stride kScanPointStride), base64 in JSON.
inline constexpr std::uint32_t kScanPointStride = 18;
std::string point_cloud_message(std::uint64_t time_ns, const std::string& frame,
                                const sensor::Scan& scan);

/// foxglove.PoseInFrame and foxglove.PosesInFrame.
std::string pose_in_frame_message(std::uint64_t time_ns, const std::string& frame,
                                  const localizer::Pose3& pose);
std::string poses_in_frame_message(std::uint64_t time_ns, const std::string& frame,
                                   const std::vector<localizer::Pose3>& poses);

/// foxglove.SceneUpdate of one entity `id` in `frame` (kept until replaced by the next entity of
/// the same id on the topic).
std::string scene_update_message(std::uint64_t time_ns, const std::string& frame,
                                 const std::string& id, const std::vector<LineStrip>& lines,
                                 const std::vector<TriangleList>& triangles);

}  // namespace conicloc::tools
