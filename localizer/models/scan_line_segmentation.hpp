#pragma once
// Scan-line segmentation for the conic-segment observation model (DESIGN.md "Linear in 1/r"): a
// measured ring is split into runs of consecutive returns that lie on one plane, each fitted by
// linear least squares on
//   1/r = a cos θ + b sin θ + c,
// and the plane is recovered from (a, b, c): n/E = (a/cos φ, b/cos φ, c/sin φ), E = −(D + n_z o).
// For φ → 0 the plane's tilt is unobservable from the ring (c → 0 whatever n_z): the segment then
// carries only the horizontal normal and the horizontal distance of the plane's trace.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "localizer/models/inverse_range_fit.hpp"
#include "sensor/scan.hpp"

namespace conicloc::localizer {

struct SegmentationConfig {
  double max_residual_m = 0.05;     ///< a return farther than this (in range) from the fit splits
  double max_relative_jump = 0.15;  ///< range jump between neighbours that always splits
  double max_gap_rad = 0.035;       ///< 2°: azimuth gap (missing returns) that always splits
  std::size_t min_returns = 8;      ///< shorter segments are dropped
  double min_range_m = 0.3;         ///< returns outside [min, the sensor's max] are ignored
  double min_sin_elevation = 1e-6;  ///< |sin φ| below this: tilt unobservable
};

struct ConicSegment {
  std::size_t first = 0;                  ///< index of the first return in RingScan::returns
  std::size_t last = 0;                   ///< index of the last return (inclusive)
  std::size_t count = 0;                  ///< valid returns used in the fit
  double begin_rad = 0.0, end_rad = 0.0;  ///< azimuth span; end_rad > 2π across θ = 0
  double a = 0.0, b = 0.0, c = 0.0;       ///< 1/r = a cos θ + b sin θ + c
  double rms_residual_m = 0.0;            ///< of the range, over the fitted returns

  bool tilt_observable = false;
  /// Plane n·p + D = 0 in the sensor frame, normal towards the sensor; only when tilt_observable.
  Eigen::Vector3d normal_sensor = Eigen::Vector3d::Zero();
  double offset_sensor = 0.0;
  /// Always set: the horizontal direction of the normal (towards the sensor) and the horizontal
  /// distance from the spin axis to the line where the plane meets the ring's cone at φ = 0
  /// (for φ ≠ 0, the distance of the line 1/r = a cos θ + b sin θ on the unit circle: cos
  /// φ/|(a,b)|).
  Eigen::Vector2d horizontal_normal = Eigen::Vector2d::Zero();
  double trace_distance_m = 0.0;
};

/// Fills the plane of a segment from its (a, b, c) and the ring's elevation and offset.
void recover_plane(ConicSegment& segment, double elevation_rad, double vertical_offset_m,
                   double min_sin_elevation = 1e-6);

/// Splits one ring (returns sorted by azimuth) into conic segments, in azimuth order starting at
/// the ring's largest range jump or gap. Returns beyond `max_range_m` (the sensor's maximum
/// range) are ignored.
std::vector<ConicSegment> segment_scan_line(const sensor::RingScan& ring,
                                            const SegmentationConfig& config, double max_range_m);

}  // namespace conicloc::localizer
