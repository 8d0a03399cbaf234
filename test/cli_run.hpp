#pragma once
// Running the real `conicloc` binary from a test, and reading the files it wrote.

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "localizer/conic/pose.hpp"

namespace conicloc::test {

/// `localize --init` for a pose: "x,y,z,yaw_deg".
inline std::string init_argument(const localizer::Pose3& pose) {
  return std::to_string(pose.translation().x()) + "," + std::to_string(pose.translation().y()) +
         "," + std::to_string(pose.translation().z()) + "," +
         std::to_string(localizer::yaw_of(pose) * 180.0 / M_PI);
}

/// The whole file as bytes ("" when it cannot be read).
inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Runs `conicloc <arguments>` with stdout and stderr into `log`. Its exit code; −1 when it did
/// not exit normally (killed by a signal: a crash).
inline int run_conicloc(const std::string& arguments, const std::filesystem::path& log) {
  const std::string command =
      std::string(CONICLOC_BINARY) + " " + arguments + " > '" + log.string() + "' 2>&1";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// The values of column `name` of a CSV file with a header line (e.g. `localize --details`);
/// empty when there is no such column.
inline std::vector<double> csv_column(const std::filesystem::path& path, const std::string& name) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::stringstream header(line);
  std::string field;
  int column = -1;
  for (int c = 0; std::getline(header, field, ','); ++c) {
    if (field == name) column = c;
  }
  std::vector<double> values;
  while (column >= 0 && std::getline(in, line)) {
    std::stringstream row(line);
    for (int c = 0; std::getline(row, field, ','); ++c) {
      if (c == column) values.push_back(std::stod(field));
    }
  }
  return values;
}

}  // namespace conicloc::test
