#include "io/scan_source.hpp"

#include "io/cloud_scan_source.hpp"
#include "io/input_error.hpp"
#include "io/packet_scan_source.hpp"

namespace conicloc::io {

std::unique_ptr<ScanSource> open_scan_source(const std::string& path,
                                             const sensor::LaserCalibration& calibration,
                                             const ScanSourceOptions& options) {
  if (auto bag = open_bag(path, options.capture.topic)) {
    // A bag keeps the packets' payloads (or the points) only: no sender to choose by.
    if (options.stream.source_address != 0) {
      throw InputError(path, bag->format,
                       "a bag records no sender address; choose the sensor by its topic");
    }
    if (is_point_cloud2_type(bag->topic.type)) {
      return std::make_unique<CloudScanSource>(std::move(*bag), calibration, options.cloud);
    }
  }
  return std::make_unique<PacketScanSource>(open_capture(path, options.capture), calibration,
                                            options);
}

}  // namespace conicloc::io
