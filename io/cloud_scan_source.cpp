#include "io/cloud_scan_source.hpp"

#include <cmath>

namespace conicloc::io {

CloudScanSource::CloudScanSource(OpenedBag bag, const sensor::LaserCalibration& calibration,
                                 CloudScanConfig config)
    : bag_(std::move(bag)), calibration_(calibration), config_(config) {}

double CloudScanSource::rotation_rpm() const {
  return turned_time_s_ > 0.0 ? turned_rad_ / (2.0 * M_PI) / turned_time_s_ * 60.0 : 0.0;
}

std::optional<sensor::Scan> CloudScanSource::next() {
  while (const auto message = bag_.reader->next()) {
    try {
      const PointCloud2View cloud = decode_point_cloud2(message->data, *bag_.topic.encoding);
      if (!time_origin_s_) time_origin_s_ = cloud.stamp_s;
      sensor::Scan scan = cloud_to_scan(cloud, calibration_, *time_origin_s_, config_);
      scan.index = next_index_++;
      const double span_s = scan.end_time_s - scan.start_time_s;
      if (span_s > 0.0) {
        turned_rad_ += 2.0 * M_PI - azimuth_gap_rad(scan);
        turned_time_s_ += span_s;
      }
      return scan;
    } catch (const MessageError& e) {
      auto& counts = bag_.reader->counts();
      ++counts.bad_messages;
      if (counts.problems.size() < CaptureCounts::kNamedProblems) {
        counts.problems.push_back(message->place + ": " + e.what() + "; skipped");
      }
    }
  }
  return std::nullopt;
}

}  // namespace conicloc::io
