#pragma once
// The JSON schemas ("jsonschema" schema encoding) of the Foxglove message types a recording uses
// (tools/foxglove_messages.hpp writes the messages). Field names and enum values
// are Foxglove's (docs.foxglove.dev, "Message schemas"); a schema lists the fields the recording
// writes. Foxglove and Lichtblick recognise a message type by its schema name
// (foxglove.PointCloud, ...), and decode a JSON "bytes" field from base64 where its schema says
// "contentEncoding": "base64".

#include <string>

namespace conicloc::tools {

std::string scene_update_schema();     ///< foxglove.SceneUpdate
std::string point_cloud_schema();      ///< foxglove.PointCloud
std::string poses_in_frame_schema();   ///< foxglove.PosesInFrame
std::string pose_in_frame_schema();    ///< foxglove.PoseInFrame
std::string frame_transform_schema();  ///< foxglove.FrameTransform

}  // namespace conicloc::tools
