#pragma once
// The filter's "lost" alarm judged against ground truth: an alarm (a recovery) raised while the
// estimate was in fact close to the truth is a false alarm, and costs a needless global search.

#include <cstddef>
#include <vector>

#include "io/tum_trajectory.hpp"

namespace conicloc::eval {

/// How many of `alarms` (the filter's estimate at each scan that raised the alarm, stamped like
/// the truth) lie within `xy_m` horizontally of the truth interpolated at their time. An alarm
/// without truth within `max_gap_s` around it is not counted: it cannot be judged.
std::size_t count_false_alarms(const std::vector<io::StampedPose>& truth,
                               const std::vector<io::StampedPose>& alarms, double max_gap_s,
                               double xy_m = 0.5);

}  // namespace conicloc::eval
