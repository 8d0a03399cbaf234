#pragma once
// One driver-style point cloud (sensor_msgs/PointCloud2 of one rotation, fields x y z, and
// optionally intensity, ring, time) as one sensor::Scan, the shape the packet path gives: one
// RingScan per laser of the calibration (indexed by elevation rank), each sorted by azimuth.
//   ring:    the `ring` field (the driver's elevation rank, 0 = lowest); without it, the laser
//            whose elevation is nearest to the point's, seen from that laser's apex.
//   azimuth: atan2(y, x) of the point, in [0, 2π); range from the laser's apex (0, 0, o_k).
//   time:    `time` is seconds after the header stamp (velodyne_pointcloud's PointXYZIRT); the
//            return's time is stamp + time − `time_origin_s` (the caller's clock origin).
// Points with a NaN or infinite coordinate or time, or at the origin, are skipped. A cloud whose
// returns leave an azimuth gap wider than `max_gap_rad` is flagged partial.

#include "io/point_cloud2_msg.hpp"
#include "sensor/laser_calibration.hpp"
#include "sensor/scan.hpp"

namespace conicloc::io {

struct CloudScanConfig {
  double max_range_m = 130.0;  ///< beyond: ReturnStatus::OutOfRange
  double max_gap_rad = 0.175;  ///< an azimuth gap wider than this (10°) makes the scan partial
};

/// The widest azimuth interval without a return, over all rings (2π for an empty scan).
double azimuth_gap_rad(const sensor::Scan& scan);

/// Throws MessageError when x, y or z is missing, or a ring is not a laser of `calibration`.
sensor::Scan cloud_to_scan(const PointCloud2View& cloud,
                           const sensor::LaserCalibration& calibration, double time_origin_s,
                           const CloudScanConfig& config = {});

}  // namespace conicloc::io
