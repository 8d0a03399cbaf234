#pragma once
// Motion de-skew: a rotation takes ~0.1 s, during which the sensor moves; every return is moved
// into the sensor frame at one reference time, assuming constant velocity over the scan.

#include "localizer/pose.hpp"
#include "sensor/scan.hpp"

namespace conicloc::localizer {

/// Returns `scan` as seen from the sensor at `reference_time_s`, given the sensor's motion
/// T_prev_curr over the `interval_s` seconds before that time (constant velocity). A return
/// fired at time t is moved by T_ref_t = scale_motion(T_prev_curr, (t − t_ref)/interval) and
/// written back in ring form: azimuth atan2(y, x) and range |p_xy| / cos φ_k, so that its
/// horizontal distance — all that the ring cone's cut with a vertical wall depends on — is
/// exact; rings stay rings (the elevation change is O(motion/range) and ignored). Returns are
/// re-sorted by azimuth. An interval ≤ 0 or an identity motion returns the scan unchanged.
sensor::Scan deskew_scan(const sensor::Scan& scan, const Pose3& T_prev_curr, double interval_s,
                         double reference_time_s);

}  // namespace conicloc::localizer
