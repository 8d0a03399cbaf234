#include "io/tum_trajectory.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

#include "io/input_error.hpp"

namespace conicloc::io {
namespace {

constexpr const char* kFieldNames[8] = {"t", "tx", "ty", "tz", "qx", "qy", "qz", "qw"};

// One field of a pose line; the message names the column so a bad value is found at once.
double parse_field(const std::string& token, std::size_t index, const std::string& name,
                   const std::string& place) {
  const std::string where =
      place + ", field " + std::to_string(index + 1) + " (" + kFieldNames[index] + ")";
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(token.c_str(), &end);
  if (end != token.c_str() + token.size() || token.empty()) {
    throw InputError(name, where, "'" + token + "' is not a number");
  }
  if (!std::isfinite(value) || (errno == ERANGE && std::abs(value) > 1.0)) {
    throw InputError(name, where, "'" + token + "' is not a finite number");
  }
  return value;
}

}  // namespace

std::vector<StampedPose> read_tum(std::istream& in, const std::string& name) {
  std::vector<StampedPose> poses;
  std::string line;
  std::size_t line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    const std::string place = "line " + std::to_string(line_number);

    std::istringstream fields(line);
    std::vector<std::string> tokens;
    for (std::string token; fields >> token;) tokens.push_back(token);
    if (tokens.size() != 8) {
      throw InputError(name, place,
                       "expected 8 numbers: t tx ty tz qx qy qz qw, found " +
                           std::to_string(tokens.size()) + " fields");
    }
    double v[8];
    for (std::size_t i = 0; i < 8; ++i) v[i] = parse_field(tokens[i], i, name, place);

    Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
    if (std::abs(q.norm() - 1.0) > 1e-3) {
      throw InputError(name, place, "quaternion norm " + std::to_string(q.norm()) + " is not 1");
    }
    if (!poses.empty() && v[0] < poses.back().time_s) {
      throw InputError(name, place,
                       "timestamp goes backwards: " + std::to_string(v[0]) + " after " +
                           std::to_string(poses.back().time_s));
    }
    StampedPose pose;
    pose.time_s = v[0];
    pose.pose.linear() = q.normalized().toRotationMatrix();
    pose.pose.translation() = Eigen::Vector3d(v[1], v[2], v[3]);
    poses.push_back(pose);
  }
  return poses;
}

std::vector<StampedPose> read_tum(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "cannot open trajectory file");
  return read_tum(in, path);
}

void write_tum_line(std::ostream& out, const StampedPose& pose) {
  const Eigen::Quaterniond q(pose.pose.linear());
  const Eigen::Vector3d& t = pose.pose.translation();
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, "%.6f %.6f %.6f %.6f %.9f %.9f %.9f %.9f\n", pose.time_s,
                t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w());
  out << buffer;
}

void write_tum(const std::string& path, const std::vector<StampedPose>& poses) {
  std::ofstream out(path);
  if (!out) throw InputError(path, "", "cannot write trajectory file");
  out << "# timestamp tx ty tz qx qy qz qw\n";
  for (const auto& pose : poses) write_tum_line(out, pose);
  if (!out) throw InputError(path, "", "write failed");
}

}  // namespace conicloc::io
