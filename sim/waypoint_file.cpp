#include "sim/waypoint_file.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "io/input_error.hpp"

namespace conicloc::sim {

std::vector<Waypoint> read_waypoints(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw io::InputError(path, "", "cannot open waypoint file");
  return read_waypoints(in, path);
}

std::vector<Waypoint> read_waypoints(std::istream& in, const std::string& name) {
  std::vector<Waypoint> waypoints;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream fields(line);
    std::vector<double> values;
    std::string token;
    while (fields >> token) {
      std::size_t used = 0;
      double value = 0.0;
      try {
        value = std::stod(token, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != token.size() || !std::isfinite(value)) {
        throw io::InputError(name, "line " + std::to_string(line_number),
                             "'" + token + "' is not a finite number");
      }
      values.push_back(value);
    }
    if (values.empty()) continue;
    if (values.size() < 2 || values.size() > 4) {
      throw io::InputError(
          name, "line " + std::to_string(line_number),
          "expected 'x y [z] [yaw_deg]', got " + std::to_string(values.size()) + " numbers");
    }
    Waypoint waypoint;
    waypoint.floor_point = {values[0], values[1], values.size() >= 3 ? values[2] : 0.0};
    if (values.size() == 4) waypoint.yaw_rad = values[3] * M_PI / 180.0;
    waypoints.push_back(waypoint);
  }
  if (waypoints.empty()) throw io::InputError(name, "", "no waypoints in file");
  return waypoints;
}

}  // namespace conicloc::sim
