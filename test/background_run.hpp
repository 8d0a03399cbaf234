#pragma once
// The real `conicloc` binary running beside the test (a live localizer waiting for packets while
// the test sends them): started with posix_spawn, stdout and stderr into files, waited for with a
// time limit (killed after it: a hang is a failure, not a stuck ctest).

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "test/cli_guarded_run.hpp"

extern char** environ;

namespace conicloc::test {

class BackgroundRun {
 public:
  /// Starts `CONICLOC_BINARY arguments...` (no shell: each argument as given).
  BackgroundRun(const std::filesystem::path& dir, const std::vector<std::string>& arguments)
      : out_(dir / "background_stdout.txt"), err_(dir / "background_stderr.txt") {
    std::vector<std::string> words = {CONICLOC_BINARY};
    words.insert(words.end(), arguments.begin(), arguments.end());
    std::vector<char*> argv;
    for (auto& word : words) argv.push_back(word.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out_.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err_.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (posix_spawn(&pid_, argv[0], &actions, nullptr, argv.data(), environ) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&actions);
  }
  ~BackgroundRun() {
    if (pid_ > 0 && !status_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  BackgroundRun(const BackgroundRun&) = delete;
  BackgroundRun& operator=(const BackgroundRun&) = delete;

  bool started() const { return pid_ > 0; }
  pid_t pid() const { return pid_; }
  std::string out() const { return file_text(out_); }
  std::string err() const { return file_text(err_); }

  /// Waits until stderr matches `pattern` (its first group), or nullopt after `limit_s` or when
  /// the program ended first.
  std::optional<std::string> wait_for_log(const std::string& pattern, double limit_s) {
    const std::regex expression(pattern);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(limit_s);
    while (std::chrono::steady_clock::now() < deadline) {
      std::smatch match;
      const std::string text = err();
      if (std::regex_search(text, match, expression)) return match.size() > 1 ? match[1] : match[0];
      if (finished()) return std::nullopt;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return std::nullopt;
  }

  /// Waits for the program to end, at most `limit_s` (then kills it: timed_out).
  GuardedRun wait(double limit_s) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(limit_s);
    GuardedRun result;
    while (!finished() && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    if (!finished()) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
      status_ = 0;
      result.timed_out = true;
    } else if (WIFSIGNALED(*status_)) {
      result.crashed = true;
    } else {
      result.exit_code = WEXITSTATUS(*status_);
    }
    result.out = out();
    result.err = err();
    return result;
  }

 private:
  bool finished() {
    if (status_) return true;
    int status = 0;
    if (pid_ <= 0) return true;
    if (::waitpid(pid_, &status, WNOHANG) == pid_) status_ = status;
    return status_.has_value();
  }

  std::filesystem::path out_, err_;
  pid_t pid_ = -1;
  std::optional<int> status_;
};

}  // namespace conicloc::test
