#pragma once
// Waypoint files: one waypoint per line, "x y [z] [yaw_deg]" (map frame, metres; z of the floor
// under the point, default 0; with a yaw the sensor stops there and turns to it). '#' starts a
// comment; blank lines are skipped. Errors throw io::InputError naming the file and line.

#include <iosfwd>
#include <string>
#include <vector>

#include "sim/trajectory.hpp"

namespace conicloc::sim {

std::vector<Waypoint> read_waypoints(const std::string& path);
std::vector<Waypoint> read_waypoints(std::istream& in, const std::string& name);

}  // namespace conicloc::sim
