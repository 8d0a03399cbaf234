#pragma once
// The fuzz input as a file on disk, for readers that cannot read through /proc/self/fd/N: SQLite
// resolves that link to "/memfd:… (deleted)", which it cannot open. One file per process under
// $TMPDIR, rewritten for every input, removed (with SQLite's side files) when the input is done.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace conicloc::fuzz {

class TempFile {
 public:
  TempFile(const std::uint8_t* data, std::size_t size)
      : path_((std::filesystem::temp_directory_path() /
               ("conicloc_fuzz_" + std::to_string(::getpid()) + ".input"))
                  .string()) {
    std::ofstream out(path_, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!out) std::abort();  // the harness cannot run at all: not a finding
  }
  ~TempFile() {
    // SQLite may leave its side files next to a database whose header asks for WAL mode.
    for (const char* suffix : {"", "-wal", "-shm", "-journal"}) {
      std::error_code ignored;
      std::filesystem::remove(path_ + suffix, ignored);
    }
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;

  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace conicloc::fuzz
