#pragma once
// The per-scan diagnostics CSV of `localize --details` (and of `localize --report-dir`): one row
// per localized scan. eval/details_csv_reader.hpp reads it back.

#include <fmt/format.h>

#include <cmath>
#include <string>

#include "localizer/filter/localizer.hpp"
#include "tools/process_memory.hpp"

namespace conicloc::tools {

inline const char* details_header() {
  return "time_s,x,y,z,qx,qy,qz,qw,var_x,var_y,var_z,var_roll,var_pitch,var_yaw,ess,particles,"
         "log_likelihood,inlier_fraction,terms,time_ms,recovered,peak_rss_mib,tempering,spread_m,"
         "see_through_fraction,status,mode_weight,effective_terms,scan_turn_deg,pose_blur_m,"
         "hypotheses_added,rings_scored,storey_share,storey_twins";
}

/// One row (with its newline) for the scan localized at UTC `utc_s`.
inline std::string details_row(double utc_s, const localizer::UpdateResult& r) {
  const Eigen::Quaterniond q(r.pose.linear());
  const Eigen::Vector3d t = r.pose.translation();
  std::string row = fmt::format("{:.6f},{:.4f},{:.4f},{:.4f},{:.9f},{:.9f},{:.9f},{:.9f}", utc_s,
                                t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w());
  for (int i = 0; i < 6; ++i) row += fmt::format(",{:.6g}", r.covariance(i, i));
  row += fmt::format(",{:.2f},{},{:.4f},{:.4f},{},{:.3f},{},{:.1f},{:.4g},{:.3f},{:.4f}", r.ess,
                     r.particles, r.log_likelihood, r.inlier_fraction, r.terms, r.run_time_ms,
                     r.recovered ? 1 : 0, peak_rss_mib(), r.tempering, r.spread_m,
                     r.see_through_fraction);
  row += fmt::format(",{},{:.4f},{:.1f},{:.4f},{:.4f},{},{},{:.4f},{}\n",
                     localizer::status_name(r.status), r.mode_weight, r.effective_terms,
                     r.scan_turn_rad * 180.0 / M_PI, r.pose_blur_m, r.hypotheses_added,
                     r.rings_scored, r.storey_share, r.storey_twins);
  return row;
}

}  // namespace conicloc::tools
