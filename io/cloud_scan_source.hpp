#pragma once
// Scans from a bag of sensor_msgs/PointCloud2 (the ROS Velodyne driver's clouds): one message,
// one scan (io/cloud_scan.hpp). Scan times count from the first cloud's stamp, which is the UTC
// offset. A message that does not decode is counted, named (first few) and skipped.

#include "io/scan_source.hpp"

namespace conicloc::io {

class CloudScanSource final : public ScanSource {
 public:
  /// `bag`: its topic a PointCloud2 topic, its reader selected on it.
  CloudScanSource(OpenedBag bag, const sensor::LaserCalibration& calibration,
                  CloudScanConfig config);

  std::optional<sensor::Scan> next() override;
  std::optional<double> utc_offset_s() const override { return time_origin_s_; }
  double rotation_rpm() const override;
  const CaptureCounts& counts() const override { return bag_.reader->counts(); }
  std::string format() const override { return bag_.format; }
  std::string name() const override { return bag_.file; }

 private:
  OpenedBag bag_;
  sensor::LaserCalibration calibration_;
  CloudScanConfig config_;
  std::optional<double> time_origin_s_;
  std::size_t next_index_ = 0;
  double turned_rad_ = 0.0;  ///< azimuth covered by the clouds so far
  double turned_time_s_ = 0.0;
};

}  // namespace conicloc::io
