#pragma once
// The process's memory high-water mark, for long-run reports.

#include <sys/resource.h>

namespace conicloc::tools {

/// Peak resident set size of this process so far, MiB (Linux reports ru_maxrss in KiB).
inline double peak_rss_mib() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0.0;
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

}  // namespace conicloc::tools
