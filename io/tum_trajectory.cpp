#include "io/tum_trajectory.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "io/input_error.hpp"

namespace conicloc::io {

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
    double v[8];
    for (double& value : v) {
      if (!(fields >> value))
        throw InputError(name, place, "expected 8 numbers: t tx ty tz qx qy qz qw");
      if (!std::isfinite(value)) throw InputError(name, place, "non-finite value");
    }
    std::string extra;
    if (fields >> extra) throw InputError(name, place, "more than 8 fields");

    Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
    if (std::abs(q.norm() - 1.0) > 1e-3) {
      throw InputError(name, place, "quaternion norm " + std::to_string(q.norm()) + " is not 1");
    }
    if (!poses.empty() && v[0] < poses.back().time_s) {
      throw InputError(name, place, "timestamp goes backwards");
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
