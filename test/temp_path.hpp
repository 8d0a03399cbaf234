#pragma once
// A temporary path private to this test process: ctest runs test cases as parallel processes,
// so fixed names in /tmp would be shared (and deleted) across them.

#include <unistd.h>

#include <filesystem>
#include <string>

namespace conicloc::test {

inline std::filesystem::path unique_temp_path(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("conicloc_" + std::to_string(::getpid()) + "_" + name);
}

}  // namespace conicloc::test
