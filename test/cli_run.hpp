#pragma once
// Running the real `conicloc` binary from a test, and reading the files it wrote.

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace conicloc::test {

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

}  // namespace conicloc::test
