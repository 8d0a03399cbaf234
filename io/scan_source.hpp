#pragma once
// Where scans come from, whatever the capture holds: Velodyne packets (pcap/pcapng, or a bag of
// velodyne_msgs/VelodyneScan) assembled into rotations, or a bag of sensor_msgs/PointCloud2 whose
// every message is one rotation. The filter loop reads scans and does not care which.
//
// Example:
//   auto source = io::open_scan_source("run.bag", calibration);
//   while (auto scan = source->next()) localizer.update(*scan);

#include <memory>
#include <optional>
#include <string>

#include "io/cloud_scan.hpp"
#include "io/open_capture.hpp"
#include "io/scan_assembler.hpp"
#include "io/velodyne_stream.hpp"

namespace conicloc::io {

class ScanSource {
 public:
  virtual ~ScanSource() = default;
  /// The next scan, or nullopt at the end of the capture.
  virtual std::optional<sensor::Scan> next() = 0;
  /// UTC − scan time (scan times are device-like: monotonic, from an arbitrary origin); nullopt
  /// before the first scan.
  virtual std::optional<double> utc_offset_s() const = 0;
  /// Mean rotation rate so far, revolutions per minute; 0 when unknown.
  virtual double rotation_rpm() const = 0;
  virtual const CaptureCounts& counts() const = 0;
  /// As CaptureSource::format().
  virtual std::string format() const = 0;
  virtual std::string name() const = 0;
  /// The packet stream behind the scans, for its statistics; nullptr for point clouds.
  virtual const VelodyneStream* stream() const { return nullptr; }
};

struct ScanSourceOptions {
  CaptureOptions capture;
  StreamConfig stream;
  ScanAssemblerConfig assembler;
  CloudScanConfig cloud;
};

/// Opens `path` (as open_capture() does) as a source of scans. Throws InputError as open_capture.
std::unique_ptr<ScanSource> open_scan_source(const std::string& path,
                                             const sensor::LaserCalibration& calibration,
                                             const ScanSourceOptions& options = {});

}  // namespace conicloc::io
