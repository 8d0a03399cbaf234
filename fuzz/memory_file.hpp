#pragma once
// The fuzz input as a file: the readers under test take a path (libpcap and pugixml read it
// themselves), so each input is written to an anonymous in-memory file (memfd) and read back
// through /proc/self/fd/N. Nothing touches the disk and nothing is left behind.

#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

namespace conicloc::fuzz {

class MemoryFile {
 public:
  MemoryFile(const std::uint8_t* data, std::size_t size) : fd_(memfd_create("fuzz_input", 0)) {
    if (fd_ < 0) std::abort();  // the harness cannot run at all: not a finding
    std::size_t written = 0;
    while (written < size) {
      const ssize_t n = write(fd_, data + written, size - written);
      if (n <= 0) std::abort();
      written += static_cast<std::size_t>(n);
    }
  }
  ~MemoryFile() { close(fd_); }
  MemoryFile(const MemoryFile&) = delete;
  MemoryFile& operator=(const MemoryFile&) = delete;

  std::string path() const { return "/proc/self/fd/" + std::to_string(fd_); }

 private:
  int fd_;
};

}  // namespace conicloc::fuzz
