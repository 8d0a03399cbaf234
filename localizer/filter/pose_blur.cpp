#include "localizer/filter/pose_blur.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <nanoflann.hpp>

namespace conicloc::localizer {

namespace {

/// The upper median of `values` (reordered): of an even count, the higher middle value, the
/// scale the blur and the refinement were measured with (median.hpp has the mean of both, for
/// small samples); 0 when empty.
double upper_median_of(std::vector<double>& values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace

double median_range_m(const sensor::Scan& scan) {
  std::vector<double> ranges;
  ranges.reserve(scan.valid_returns());
  for (const sensor::RingScan& ring : scan.rings) {
    for (const sensor::Return& ret : ring.returns) {
      if (ret.status == sensor::ReturnStatus::Valid) ranges.push_back(ret.range_m);
    }
  }
  return upper_median_of(ranges);
}

double cloud_pose_blur_m(const ParticleSet& particles, double range_m) {
  const std::size_t n = particles.size();
  if (n < 2) return 0.0;
  using Points = Eigen::Matrix<double, Eigen::Dynamic, 5, Eigen::RowMajor>;
  Points points(static_cast<Eigen::Index>(n), 5);
  for (std::size_t i = 0; i < n; ++i) {
    const PoseState& s = particles[i].state;
    points.row(static_cast<Eigen::Index>(i)) << s.x, s.y, s.z, range_m * std::cos(s.yaw),
        range_m * std::sin(s.yaw);
  }
  using Tree = nanoflann::KDTreeEigenMatrixAdaptor<Points, 5, nanoflann::metric_L2_Simple>;
  const Tree tree(5, std::cref(points), 16);
  std::vector<double> nearest(n);
  for (std::size_t i = 0; i < n; ++i) {
    // Two neighbours: the particle itself (distance 0) and the nearest other one. Resampled
    // copies of one particle are another particle at distance 0: the cloud is that dense there.
    Eigen::Index index[2];
    double squared[2];
    const Eigen::Matrix<double, 1, 5> query = points.row(static_cast<Eigen::Index>(i));
    const auto found = tree.index->knnSearch(query.data(), 2, index, squared);
    nearest[i] = found == 2 ? std::sqrt(squared[1]) : 0.0;
  }
  return upper_median_of(nearest);
}

}  // namespace conicloc::localizer
