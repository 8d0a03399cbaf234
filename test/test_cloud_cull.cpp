// The candidates of a particle cloud (localizer/conic/cloud_cull.hpp): the region culled is kept
// while it holds the cloud's grown box and is not much wider, replaced otherwise, and the version
// changes exactly when the candidates do.
#include <gtest/gtest.h>

#include "io/indoorgml.hpp"
#include "localizer/conic/cloud_cull.hpp"
#include "test/synthetic_room.hpp"

namespace cl = conicloc::localizer;
namespace ct = conicloc::test;

namespace {

Eigen::AlignedBox3d box_at(double x, double y, double half_m) {
  const Eigen::Vector3d centre(x, y, 1.0);
  return {centre - Eigen::Vector3d::Constant(half_m), centre + Eigen::Vector3d::Constant(half_m)};
}

}  // namespace

TEST(CloudCull, KeepsItsRegionWhileItHoldsTheCloud) {
  const auto map = conicloc::io::load_indoorgml(CONICLOC_EXAMPLE_MAP).map;
  const conicloc::maps::PlaneIndex index(map);
  const cl::PlaneCuller culler(map, index, ct::vlp16());
  cl::CloudCull cull(0.5, 1.0);
  const Eigen::Vector3d middle = map.bounds.center();
  ASSERT_TRUE(cull.update(culler, box_at(middle.x(), middle.y(), 0.2)));
  const Eigen::AlignedBox3d first = cull.region();
  EXPECT_TRUE(first.contains(box_at(middle.x(), middle.y(), 0.2 + 0.5 + 1.0 - 1e-9)));
  EXPECT_EQ(cull.candidates(), culler.cull(first).kept);
  const std::uint64_t version = cull.version();
  // 0.9 m on: the grown box still lies in the region, nothing is culled again.
  EXPECT_FALSE(cull.update(culler, box_at(middle.x() + 0.9, middle.y(), 0.2)));
  EXPECT_TRUE(cull.region().isApprox(first));
  EXPECT_EQ(cull.version(), version);
  // 1.2 m on, it does not: a region about the new box.
  cull.update(culler, box_at(middle.x() + 1.2, middle.y(), 0.2));
  EXPECT_FALSE(cull.region().isApprox(first));
  EXPECT_TRUE(cull.region().contains(box_at(middle.x() + 1.2, middle.y(), 1.7 - 1e-9)));
  EXPECT_EQ(cull.candidates(), culler.cull(cull.region()).kept);
  // A wide cloud, then one that shrank to a point within it: culled again for the point.
  cull.update(culler, box_at(middle.x(), middle.y(), 5.0));
  const Eigen::AlignedBox3d wide = cull.region();
  cull.update(culler, box_at(middle.x(), middle.y(), 0.0));
  EXPECT_TRUE(wide.contains(cull.region()));
  EXPECT_LT(cull.region().sizes().x(), 3.0 + 1e-9);
  // No cloud: no candidates, a new version; the same again: the same version.
  const std::uint64_t before = cull.version();
  EXPECT_TRUE(cull.update(culler, Eigen::AlignedBox3d()));
  EXPECT_TRUE(cull.candidates().empty());
  EXPECT_GT(cull.version(), before);
  EXPECT_FALSE(cull.update(culler, Eigen::AlignedBox3d()));
}

// Far apart in a room much larger than the sensor's range, two clouds see other polygons:
// the candidates change and so does the version; back where the first region was culled, the
// candidates are the first ones again, under a new version.
TEST(CloudCull, TheVersionChangesWithTheCandidates) {
  const auto map = ct::make_box_room();
  const conicloc::maps::PlaneIndex index(map);
  const cl::PlaneCuller culler(map, index, ct::vlp16(), {}, 2.0);  // a 2 m sensor, a 10 m room
  cl::CloudCull cull(0.5, 1.0);
  ASSERT_TRUE(cull.update(culler, box_at(1.0, 1.0, 0.0)));
  const std::vector<int> corner = cull.candidates();
  const std::uint64_t first = cull.version();
  ASSERT_TRUE(cull.update(culler, box_at(5.0, 4.0, 0.0)));
  EXPECT_NE(cull.candidates(), corner);
  EXPECT_GT(cull.version(), first);
  const std::uint64_t second = cull.version();
  ASSERT_TRUE(cull.update(culler, box_at(1.0, 1.0, 0.0)));
  EXPECT_EQ(cull.candidates(), corner);
  EXPECT_GT(cull.version(), second);
}
