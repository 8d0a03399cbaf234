#pragma once
// One pose as one line of JSON, for `localize --pose-udp` (a datagram per scan):
//   {"time":1700000000.123456,"pose":{"x":..,"y":..,"z":..,"qx":..,"qy":..,"qz":..,"qw":..},
//    "covariance":[36 numbers],"status":"tracking"}
// time: UTC seconds of the scan's end; pose: T_map_sensor, metres and a unit quaternion;
// covariance: 6×6 row-major over (x, y, z, roll, pitch, yaw), m², m·rad, rad²; status: the
// localizer's (localizer::status_name).

#include <Eigen/Geometry>
#include <sstream>
#include <string>

#include "localizer/filter/localizer.hpp"
#include "tools/json_writer.hpp"

namespace conicloc::tools {

inline std::string pose_json_line(double utc_s, const localizer::UpdateResult& result) {
  std::ostringstream text;
  JsonWriter json(text);
  const Eigen::Quaterniond q(result.pose.linear());
  const Eigen::Vector3d t = result.pose.translation();
  json.begin_object();
  json.key("time").value(utc_s);
  json.key("pose").begin_object();
  json.key("x").value(t.x()).key("y").value(t.y()).key("z").value(t.z());
  json.key("qx").value(q.x()).key("qy").value(q.y()).key("qz").value(q.z()).key("qw").value(q.w());
  json.end_object();
  json.key("covariance").begin_array();
  for (int row = 0; row < 6; ++row) {
    for (int col = 0; col < 6; ++col) json.value(result.covariance(row, col));
  }
  json.end_array();
  json.key("status").value(localizer::status_name(result.status));
  json.end_object();
  text << '\n';
  return text.str();
}

}  // namespace conicloc::tools
