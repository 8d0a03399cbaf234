#include "tools/foxglove_schemas.hpp"

#include <initializer_list>
#include <string_view>
#include <utility>

namespace conicloc::tools {
namespace {

using Properties = std::initializer_list<std::pair<std::string_view, std::string>>;

// Built by appending: GCC 12 warns (wrongly, -Wrestrict) on "literal" + std::string&&.
std::string quoted(std::string_view text) {
  std::string out(1, '"');
  out.append(text);
  out += '"';
  return out;
}

std::string object(std::string_view title, Properties properties) {
  std::string text = "{\"title\":";
  text += quoted(title);
  text += ",\"type\":\"object\",\"properties\":{";
  bool first = true;
  for (const auto& [name, schema] : properties) {
    if (!first) text += ',';
    text += quoted(name);
    text += ':';
    text += schema;
    first = false;
  }
  return text + "}}";
}

std::string array(const std::string& items) {
  return "{\"type\":\"array\",\"items\":" + items + "}";
}

std::string number() {
  return "{\"type\":\"number\"}";
}
std::string integer() {
  return "{\"type\":\"integer\",\"minimum\":0}";
}
std::string string() {
  return "{\"type\":\"string\"}";
}
std::string boolean() {
  return "{\"type\":\"boolean\"}";
}
std::string bytes() {
  return "{\"type\":\"string\",\"contentEncoding\":\"base64\"}";
}

std::string enumeration(std::string_view title,
                        std::initializer_list<std::pair<std::string_view, int>> values) {
  std::string text = "{\"title\":";
  text += quoted(title);
  text += ",\"oneOf\":[";
  bool first = true;
  for (const auto& [name, value] : values) {
    text += std::string(first ? "" : ",") + "{\"title\":" + quoted(name) +
            ",\"const\":" + std::to_string(value) + "}";
    first = false;
  }
  return text + "]}";
}

std::string time() {
  return "{\"type\":\"object\",\"title\":\"time\",\"properties\":{\"sec\":" + integer() +
         ",\"nsec\":{\"type\":\"integer\",\"minimum\":0,\"maximum\":999999999}}}";
}
std::string duration() {
  return "{\"type\":\"object\",\"title\":\"duration\",\"properties\":{\"sec\":{\"type\":"
         "\"integer\"},\"nsec\":{\"type\":\"integer\",\"minimum\":0,\"maximum\":999999999}}}";
}

std::string vector3(std::string_view title) {
  return object(title, {{"x", number()}, {"y", number()}, {"z", number()}});
}
std::string quaternion() {
  return object("foxglove.Quaternion",
                {{"x", number()}, {"y", number()}, {"z", number()}, {"w", number()}});
}
std::string pose() {
  return object("foxglove.Pose",
                {{"position", vector3("foxglove.Vector3")}, {"orientation", quaternion()}});
}
std::string color() {
  return object("foxglove.Color",
                {{"r", number()}, {"g", number()}, {"b", number()}, {"a", number()}});
}

std::string line_primitive() {
  return object("foxglove.LinePrimitive",
                {{"type", enumeration("foxglove.LineType",
                                      {{"LINE_STRIP", 0}, {"LINE_LOOP", 1}, {"LINE_LIST", 2}})},
                 {"pose", pose()},
                 {"thickness", number()},
                 {"scale_invariant", boolean()},
                 {"points", array(vector3("foxglove.Point3"))},
                 {"color", color()},
                 {"colors", array(color())},
                 {"indices", array(integer())}});
}

std::string triangle_list_primitive() {
  return object("foxglove.TriangleListPrimitive", {{"pose", pose()},
                                                   {"points", array(vector3("foxglove.Point3"))},
                                                   {"color", color()},
                                                   {"colors", array(color())},
                                                   {"indices", array(integer())}});
}

/// A primitive list the recording leaves empty: its items named, their fields not listed (a
/// viewer's schema parser still wants every object's "properties").
std::string unused(std::string_view title) {
  return array(object(title, {}));
}

std::string scene_entity() {
  return object("foxglove.SceneEntity",
                {{"timestamp", time()},
                 {"frame_id", string()},
                 {"id", string()},
                 {"lifetime", duration()},
                 {"frame_locked", boolean()},
                 {"metadata",
                  array(object("foxglove.KeyValuePair", {{"key", string()}, {"value", string()}}))},
                 {"arrows", unused("foxglove.ArrowPrimitive")},
                 {"cubes", unused("foxglove.CubePrimitive")},
                 {"spheres", unused("foxglove.SpherePrimitive")},
                 {"cylinders", unused("foxglove.CylinderPrimitive")},
                 {"lines", array(line_primitive())},
                 {"triangles", array(triangle_list_primitive())},
                 {"texts", unused("foxglove.TextPrimitive")},
                 {"models", unused("foxglove.ModelPrimitive")}});
}

}  // namespace

std::string scene_update_schema() {
  return object(
      "foxglove.SceneUpdate",
      {{"deletions", array(object("foxglove.SceneEntityDeletion",
                                  {{"timestamp", time()},
                                   {"type", enumeration("foxglove.SceneEntityDeletionType",
                                                        {{"MATCHING_ID", 0}, {"ALL", 1}})},
                                   {"id", string()}}))},
       {"entities", array(scene_entity())}});
}

std::string point_cloud_schema() {
  const std::string numeric_type = enumeration("foxglove.NumericType", {{"UNKNOWN", 0},
                                                                        {"UINT8", 1},
                                                                        {"INT8", 2},
                                                                        {"UINT16", 3},
                                                                        {"INT16", 4},
                                                                        {"UINT32", 5},
                                                                        {"INT32", 6},
                                                                        {"FLOAT32", 7},
                                                                        {"FLOAT64", 8}});
  return object(
      "foxglove.PointCloud",
      {{"timestamp", time()},
       {"frame_id", string()},
       {"pose", pose()},
       {"point_stride", integer()},
       {"fields",
        array(object("foxglove.PackedElementField",
                     {{"name", string()}, {"offset", integer()}, {"type", numeric_type}}))},
       {"data", bytes()}});
}

std::string poses_in_frame_schema() {
  return object("foxglove.PosesInFrame",
                {{"timestamp", time()}, {"frame_id", string()}, {"poses", array(pose())}});
}

std::string pose_in_frame_schema() {
  return object("foxglove.PoseInFrame",
                {{"timestamp", time()}, {"frame_id", string()}, {"pose", pose()}});
}

std::string frame_transform_schema() {
  return object("foxglove.FrameTransform", {{"timestamp", time()},
                                            {"parent_frame_id", string()},
                                            {"child_frame_id", string()},
                                            {"translation", vector3("foxglove.Vector3")},
                                            {"rotation", quaternion()}});
}

}  // namespace conicloc::tools
