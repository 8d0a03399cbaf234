#pragma once
// Groups decoded points into scans, one per rotation (the paper's m × n range matrix: one RingScan
// per laser, sorted by azimuth). A scan ends where the firing azimuth crosses `cut_azimuth_rad`.
// The first and last rotations of a stream, and rotations with lost packets, are flagged partial.
// No-returns (range 0) and returns beyond `max_range_m` are kept with their status, so every ring
// keeps one entry per firing. Times are the stream's (already monotonic) device times.
//
// Example:
//   io::ScanAssembler assembler(calibration, {.cut_azimuth_rad = M_PI});   // cut behind the sensor
//   std::vector<sensor::Scan> scans;
//   while (stream.next(points)) assembler.add(points, scans);
//   if (auto last = assembler.finish()) scans.push_back(std::move(*last));

#include <optional>
#include <span>
#include <vector>

#include "io/velodyne_decoder.hpp"
#include "sensor/scan.hpp"

namespace conicloc::io {

struct ScanAssemblerConfig {
  double cut_azimuth_rad = 0.0;        ///< REP-103 azimuth where a rotation starts/ends
  double max_range_m = 130.0;          ///< beyond: ReturnStatus::OutOfRange
  double min_range_m = 0.0;            ///< below (but > 0): OutOfRange (e.g. the vehicle itself)
  int full_turn_tolerance_cdeg = 400;  ///< a scan missing more than this is partial (0.01°)
  double max_time_gap_s = 0.25;        ///< silence longer than this ends the scan (partial)
};

/// sensor::ReturnKind of a decoded label: last echoes (and identical dual pairs) are Last, the
/// strongest echo of a dual pair is Dual.
sensor::ReturnKind return_kind(velodyne::ReturnLabel label);

class ScanAssembler {
 public:
  ScanAssembler(const sensor::LaserCalibration& calibration, ScanAssemblerConfig config = {});

  /// Adds points in firing order; scans completed by them are appended to `completed`.
  void add(std::span<const DecodedPoint> points, std::vector<sensor::Scan>& completed);

  /// Ends the stream: the open scan, if any (flagged partial unless it covers a full turn).
  std::optional<sensor::Scan> finish();

 private:
  void start_scan();
  sensor::Scan close_scan();

  sensor::LaserCalibration calibration_;
  ScanAssemblerConfig config_;
  int cut_cdeg_ = 0;  ///< Velodyne azimuth of the cut
  std::optional<sensor::Scan> open_;
  std::size_t next_index_ = 0;
  int first_rel_ = 0;  ///< first firing's azimuth past the cut (0.01°)
  int last_rel_ = 0;
  int missing_cdeg_ = 0;  ///< azimuth skipped inside the scan (lost packets)
  double last_time_s_ = 0.0;
};

}  // namespace conicloc::io
