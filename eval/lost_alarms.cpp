#include "eval/lost_alarms.hpp"

#include "eval/trajectory_metrics.hpp"

namespace conicloc::eval {

std::size_t count_false_alarms(const std::vector<io::StampedPose>& truth,
                               const std::vector<io::StampedPose>& alarms, double max_gap_s,
                               double xy_m) {
  std::size_t count = 0;
  for (const auto& alarm : alarms) {
    const auto truth_pose = interpolate_pose(truth, alarm.time_s, max_gap_s);
    if (!truth_pose) continue;
    const Eigen::Vector3d d = alarm.pose.translation() - truth_pose->translation();
    count += d.head<2>().norm() < xy_m ? 1 : 0;
  }
  return count;
}

}  // namespace conicloc::eval
