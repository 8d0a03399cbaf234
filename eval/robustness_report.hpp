#pragma once
// The robustness tables of an evaluation sweep (issue 14): lost runs, error, recoveries, false
// alarms and time per model × building × scenario, and per model × scenario the targets as
// pass/fail.

#include <string>
#include <vector>

#include "eval/sweep_report.hpp"

namespace conicloc::eval {

/// Issue 14's limits.
struct RobustnessTargets {
  double lost_xy_m =
      0.5;  ///< tracking: lost once the xy error exceeds it; also the false-alarm limit
  double xy_rmse_m = 0.05;
  double heading_rmse_deg = 0.5;
  double settle_within_s = 10.0;  ///< global start / kidnap: at ≤ 10 cm within this time
  double settle_share = 0.95;     ///< ... in at least this share of the runs
};

/// The run's row in the robustness table: building_group, or the building when that is empty.
std::string building_group_of(const RunRecord& run);

/// Lost: a failed run; a tracking run whose xy error ever exceeds `lost_xy_m` (or that matched no
/// estimate); a global-start or kidnap run not settled at ≤ 10 cm (time_to_10cm_s) within
/// `settle_within_s`.
bool lost_run(const RunRecord& run, const RobustnessTargets& targets = {});

/// Markdown (`##` sections): the table per model × building group × scenario over seeds, the
/// targets per model × scenario over all buildings, and the lost alarm's false-alarm rate per
/// model over the tracking scenarios. Failed runs count as runs and as lost, and stay out of the
/// means.
std::string robustness_markdown(const std::vector<RunRecord>& runs,
                                const RobustnessTargets& targets = {});

}  // namespace conicloc::eval
