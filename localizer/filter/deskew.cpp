#include "localizer/filter/deskew.hpp"

#include <algorithm>
#include <cmath>

#include "localizer/filter/relative_motion.hpp"
#include "parallel/parallel_for.hpp"
#include "sensor/azimuth_order.hpp"

namespace conicloc::localizer {

sensor::Scan deskew_scan(const sensor::Scan& scan, const Pose3& T_prev_curr, double interval_s,
                         double reference_time_s, int threads) {
  sensor::Scan out;
  deskew_scan_into(scan, T_prev_curr, interval_s, reference_time_s, threads, out);
  return out;
}

void deskew_scan_into(const sensor::Scan& scan, const Pose3& T_prev_curr, double interval_s,
                      double reference_time_s, int threads, sensor::Scan& out) {
  out = scan;  // copy-assigning keeps the capacity of out's rings
  if (!(interval_s > 0.0) || T_prev_curr.isApprox(Pose3::Identity(), 1e-12)) return;
  // The fractions of the interval the returns were fired at span [lo, hi] (a time that is not a
  // number moves its own return to no number, not the others).
  double lo = 0.0, hi = 0.0;
  bool any = false;
  for (const sensor::RingScan& ring : scan.rings) {
    for (const sensor::Return& ret : ring.returns) {
      const double fraction = (ret.time_s - reference_time_s) / interval_s;
      if (!std::isfinite(fraction)) continue;
      lo = any ? std::min(lo, fraction) : fraction;
      hi = any ? std::max(hi, fraction) : fraction;
      any = true;
    }
  }
  const TabulatedMotion motion(ConstantVelocityMotion(T_prev_curr), lo, hi);
  // Rings are independent: each is moved and re-sorted by one worker (same result for any count).
  parallel_for(out.rings.size(), threads, [&](std::size_t begin, std::size_t end, int) {
    for (std::size_t r = begin; r < end; ++r) {
      sensor::RingScan& ring = out.rings[r];
      const double cos_elevation = std::cos(ring.elevation_rad);
      const double sin_elevation = std::sin(ring.elevation_rad);
      for (sensor::Return& ret : ring.returns) {
        const double fraction = (ret.time_s - reference_time_s) / interval_s;
        if (ret.status != sensor::ReturnStatus::Valid) {
          // No point to move: only the heading of the beam changes.
          ret.azimuth_rad = std::fmod(ret.azimuth_rad + motion.yaw(fraction), 2.0 * M_PI);
        } else {
          const Eigen::Vector3d p_ref =
              motion.apply(fraction, sensor::sensor_point(ring, ret, cos_elevation, sin_elevation));
          ret.azimuth_rad = std::atan2(p_ref.y(), p_ref.x());
          const double horizontal = std::hypot(p_ref.x(), p_ref.y());
          ret.range_m = cos_elevation > 1e-6
                            ? horizontal / cos_elevation
                            : (p_ref - Eigen::Vector3d(0, 0, ring.vertical_offset_m)).norm();
        }
        // Into [0, 2π): atan2 gives [−π, π], the fmod above (−2π, 2π).
        if (ret.azimuth_rad < 0.0) ret.azimuth_rad += 2.0 * M_PI;
      }
      sensor::sort_by_azimuth(ring.returns);
    }
  });
}

double mean_return_time_fraction(const sensor::Scan& scan, double interval_s,
                                 double reference_time_s) {
  if (!(interval_s > 0.0)) return 0.0;
  double fraction_sum = 0.0;
  std::size_t valid = 0;
  for (const sensor::RingScan& ring : scan.rings) {
    for (const sensor::Return& ret : ring.returns) {
      if (ret.status != sensor::ReturnStatus::Valid) continue;
      fraction_sum += (ret.time_s - reference_time_s) / interval_s;
      ++valid;
    }
  }
  return valid > 0 ? fraction_sum / static_cast<double>(valid) : 0.0;
}

}  // namespace conicloc::localizer
