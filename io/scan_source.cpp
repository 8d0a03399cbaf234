#include "io/scan_source.hpp"

#include "io/cloud_scan_source.hpp"
#include "io/packet_scan_source.hpp"

namespace conicloc::io {

std::unique_ptr<ScanSource> open_scan_source(const std::string& path,
                                             const sensor::LaserCalibration& calibration,
                                             const ScanSourceOptions& options) {
  if (auto bag = open_bag(path, options.capture.topic);
      bag && is_point_cloud2_type(bag->topic.type)) {
    return std::make_unique<CloudScanSource>(std::move(*bag), calibration, options.cloud);
  }
  return std::make_unique<PacketScanSource>(open_capture(path, options.capture), calibration,
                                            options);
}

}  // namespace conicloc::io
