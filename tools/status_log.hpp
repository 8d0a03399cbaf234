#pragma once
// What `conicloc localize` tells the user about the filter's certainty: a log line whenever the
// status changes (tracking, uncertain, lost, relocalizing) and when the filter first converges,
// and the per-scan covariance rows of `--covariance`.

#include <spdlog/spdlog.h>

#include <optional>
#include <string>

#include "localizer/filter/localizer.hpp"

namespace conicloc::tools {

/// "time_s,cov_x_x,cov_x_y,…,cov_yaw_yaw": the 21 entries of the upper triangle, row by row.
inline std::string covariance_header() {
  static const char* kAxes[] = {"x", "y", "z", "roll", "pitch", "yaw"};
  std::string header = "time_s";
  for (int i = 0; i < 6; ++i) {
    for (int j = i; j < 6; ++j) header += fmt::format(",cov_{}_{}", kAxes[i], kAxes[j]);
  }
  return header;
}

inline std::string covariance_row(double time_s, const localizer::Matrix6& covariance) {
  std::string row = fmt::format("{:.6f}", time_s);
  for (int i = 0; i < 6; ++i) {
    for (int j = i; j < 6; ++j) row += fmt::format(",{:.6g}", covariance(i, j));
  }
  return row;
}

class StatusLog {
 public:
  /// `elapsed_s`: seconds since the first scan of the run.
  void update(double elapsed_s, const localizer::UpdateResult& result) {
    if (!status_ || *status_ != result.status) {
      spdlog::info("{:8.2f} s: status {} (xy std. dev. {:.2f} m, {} particles)", elapsed_s,
                   localizer::status_name(result.status), result.spread_m, result.particles);
      status_ = result.status;
    }
    if (!converged_s_ && result.status == localizer::LocalizerStatus::Tracking) {
      converged_s_ = elapsed_s;
      spdlog::info("converged after {:.2f} s of data", elapsed_s);
    }
  }
  void finish() const {
    if (!converged_s_) spdlog::warn("the filter never converged (status never 'tracking')");
  }

 private:
  std::optional<localizer::LocalizerStatus> status_;
  std::optional<double> converged_s_;
};

}  // namespace conicloc::tools
