#pragma once
// Motion de-skew: a rotation takes ~0.1 s, during which the sensor moves; every return is moved
// into the sensor frame at one reference time, assuming constant velocity over the scan.

#include "localizer/conic/pose.hpp"
#include "sensor/scan.hpp"

namespace conicloc::localizer {

/// Returns `scan` as seen from the sensor at `reference_time_s`, given the sensor's motion
/// T_prev_curr over the `interval_s` seconds before that time (constant velocity). A return
/// fired at time t is moved by T_ref_t = scale_motion(T_prev_curr, (t − t_ref)/interval) (to
/// ~10⁻⁹ rad: TabulatedMotion, relative_motion.hpp) and
/// written back in ring form: azimuth atan2(y, x) and range |p_xy| / cos φ_k, so that its
/// horizontal distance — all that the ring cone's cut with a vertical wall depends on — is
/// exact; rings stay rings (the elevation change is O(motion/range) and ignored). Returns are
/// re-sorted by azimuth. An interval ≤ 0 or an identity motion returns the scan unchanged.
/// `threads` workers share the rings (parallel_for.hpp); the result is the same for any count.
sensor::Scan deskew_scan(const sensor::Scan& scan, const Pose3& T_prev_curr, double interval_s,
                         double reference_time_s, int threads = 1);

/// The same into `out`, whose rings' storage is reused: a scan's returns (~1 MB) allocated anew
/// each scan and freed again cost page faults — as much as moving them (bench_localizer
/// DeskewScan). `out` may be `scan` (it is then de-skewed in place).
void deskew_scan_into(const sensor::Scan& scan, const Pose3& T_prev_curr, double interval_s,
                      double reference_time_s, int threads, sensor::Scan& out);

/// The mean over the valid returns of (t − reference_time) / interval (≤ 0 for returns before
/// the reference time; −0.5 for returns fired evenly over the interval). deskew_scan() keeps
/// every return on its ring, so a return keeps the height it was fired from: a scan taken while
/// climbing Δz over the interval is seen, on average, from this fraction × Δz above the
/// reference pose (the spread, ±Δz/2, is left as noise). 0 for an interval ≤ 0 or no valid return.
double mean_return_time_fraction(const sensor::Scan& scan, double interval_s,
                                 double reference_time_s);

}  // namespace conicloc::localizer
