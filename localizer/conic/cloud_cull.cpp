#include "localizer/conic/cloud_cull.hpp"

namespace conicloc::localizer {

CloudCull::CloudCull(double margin_m, double slack_m) : margin_m_(margin_m), slack_m_(slack_m) {}

bool CloudCull::update(const PlaneCuller& culler, const Eigen::AlignedBox3d& cloud_box) {
  std::vector<int> candidates;
  if (cloud_box.isEmpty()) {
    region_.setEmpty();
  } else {
    Eigen::AlignedBox3d needed = cloud_box;
    needed.min().array() -= margin_m_;
    needed.max().array() += margin_m_;
    const bool holds = !region_.isEmpty() && region_.contains(needed);
    const bool too_wide = holds && ((needed.min() - region_.min()).maxCoeff() > 2.0 * slack_m_ ||
                                    (region_.max() - needed.max()).maxCoeff() > 2.0 * slack_m_);
    if (holds && !too_wide) return false;
    region_ = needed;
    region_.min().array() -= slack_m_;
    region_.max().array() += slack_m_;
    candidates = culler.cull(region_).kept;
  }
  if (candidates == candidates_) return false;
  candidates_ = std::move(candidates);
  ++version_;
  return true;
}

}  // namespace conicloc::localizer
