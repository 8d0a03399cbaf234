#pragma once
// Runs the real `conicloc` binary with a time limit (coreutils `timeout`), stdout and stderr
// captured apart in a directory private to the test, and an exit status that tells a chosen exit
// from a crash (a signal: segfault, abort, sanitizer report) or a hang.

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace conicloc::test {

struct GuardedRun {
  int exit_code = -1;      ///< the program's exit status when it exited by itself
  bool crashed = false;    ///< ended by a signal
  bool timed_out = false;  ///< killed by the time limit
  std::string out, err;

  /// An exit the program chose: not a signal, not the time limit.
  bool clean_exit() const { return !crashed && !timed_out && exit_code >= 0; }
};

inline std::string file_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Runs `CONICLOC_BINARY arguments` in the shell (quote paths in `arguments`).
inline GuardedRun run_guarded(const std::filesystem::path& dir, const std::string& arguments,
                              int time_limit_s = 120) {
  const auto out = dir / "cli_stdout.txt";
  const auto err = dir / "cli_stderr.txt";
  const std::string command = "timeout -k 5 " + std::to_string(time_limit_s) + " " +
                              std::string(CONICLOC_BINARY) + " " + arguments + " > '" +
                              out.string() + "' 2> '" + err.string() + "'";
  const int status = std::system(command.c_str());
  GuardedRun result;
  result.out = file_text(out);
  result.err = file_text(err);
  if (status == -1 || WIFSIGNALED(status)) {
    result.crashed = true;
    return result;
  }
  const int code = WEXITSTATUS(status);
  // timeout(1): 124 on expiry, 137 after -k, 128+n when the program died of signal n.
  if (code == 124 || code == 137) {
    result.timed_out = true;
  } else if (code > 128) {
    result.crashed = true;
  } else {
    result.exit_code = code;
  }
  return result;
}

}  // namespace conicloc::test
