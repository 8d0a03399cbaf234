#include "io/packet_scan_source.hpp"

namespace conicloc::io {

PacketScanSource::PacketScanSource(std::unique_ptr<CaptureSource> capture,
                                   const sensor::LaserCalibration& calibration,
                                   const ScanSourceOptions& options)
    : capture_(std::move(capture)),
      timed_(*capture_),
      stream_(timed_, calibration, options.stream),
      assembler_(calibration, options.assembler) {}

std::optional<sensor::Scan> PacketScanSource::next() {
  std::vector<sensor::Scan> completed;
  while (ready_.empty() && !ended_) {
    if (!stream_.next(points_)) {
      ended_ = true;
      if (auto last = assembler_.finish()) ready_.push_back(std::move(*last));
      break;
    }
    if (!utc_offset_s_ && !points_.empty()) {
      utc_offset_s_ = timed_.last_capture_time_s - points_.back().time_s;
    }
    assembler_.add(points_, completed);
    for (auto& scan : completed) ready_.push_back(std::move(scan));
    completed.clear();
  }
  if (ready_.empty()) return std::nullopt;
  sensor::Scan scan = std::move(ready_.front());
  ready_.pop_front();
  return scan;
}

}  // namespace conicloc::io
