#pragma once
// The polygons a particle cloud can see, for the predictions its association cells share. The
// cloud's box grown by a margin (its motion before the next scan) is culled with room to spare,
// and that region is kept while it holds the box: a tracked cloud, which moves a few centimetres
// per scan, keeps its candidates for many scans, and with them the cells' predictions
// (YawSharedPrediction keeps a prediction while the candidates it was made from are the same).

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "localizer/conic/plane_culling.hpp"

namespace conicloc::localizer {

class CloudCull {
 public:
  /// `margin_m`: the cloud's box is grown by this before it must lie in the region; `slack_m`:
  /// a new region is that grown box grown by this, kept until the grown box leaves it or it is
  /// more than twice this wider than the grown box on some side (a cloud that shrank).
  CloudCull(double margin_m, double slack_m);

  /// The candidates for a cloud in `cloud_box` (map frame; empty: none). Returns true when they
  /// changed.
  bool update(const PlaneCuller& culler, const Eigen::AlignedBox3d& cloud_box);

  const std::vector<int>& candidates() const { return candidates_; }
  /// Changes exactly when the candidates do.
  std::uint64_t version() const { return version_; }
  const Eigen::AlignedBox3d& region() const { return region_; }

 private:
  double margin_m_, slack_m_;
  Eigen::AlignedBox3d region_;  ///< culled for; empty before the first cloud
  std::vector<int> candidates_;
  std::uint64_t version_ = 0;
};

}  // namespace conicloc::localizer
