// The pose blur of a sparse cloud (localizer/pose_blur.hpp): the median spacing of the
// particles, yaw counted at the scan's range; and the models widened by it, exactly undone by 0.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "box_room_scan.hpp"
#include "localizer/filter/pose_blur.hpp"
#include "localizer/models/observation_factory.hpp"

namespace cl = conicloc::localizer;
namespace ct = conicloc::test;

namespace {}  // namespace

TEST(PoseBlur, IsTheMedianDistanceToTheNearestParticle) {
  cl::ParticleSet cloud;
  for (int i = 0; i < 9; ++i) cloud.push_back(ct::particle_at(1.0 * i, 0.0, 0.3, 1.0));
  // One outlier far away does not move the median.
  cloud.push_back(ct::particle_at(50.0, 50.0, 0.3, 1.0));
  EXPECT_DOUBLE_EQ(cl::cloud_pose_blur_m(cloud, 8.0), 1.0);
}

TEST(PoseBlur, CountsYawAsTheChordItMovesAReturnAtTheScanRange) {
  const cl::ParticleSet cloud{ct::particle_at(2.0, 3.0, 0.0, 1.0),
                              ct::particle_at(2.0, 3.0, 0.1, 1.0)};
  // |r̄(cos a, sin a) − r̄(cos b, sin b)| = 2 r̄ sin(|a − b| / 2).
  EXPECT_NEAR(cl::cloud_pose_blur_m(cloud, 10.0), 2.0 * 10.0 * std::sin(0.05), 1e-12);
  // Across ±π the chord is short, as the angle is.
  const cl::ParticleSet across{ct::particle_at(0.0, 0.0, M_PI - 0.05, 1.0),
                               ct::particle_at(0.0, 0.0, -M_PI + 0.05, 1.0)};
  EXPECT_NEAR(cl::cloud_pose_blur_m(across, 10.0), 2.0 * 10.0 * std::sin(0.05), 1e-9);
}

TEST(PoseBlur, IsZeroForOneParticleOrCopies) {
  EXPECT_EQ(cl::cloud_pose_blur_m({ct::particle_at(1.0, 1.0, 0.0, 1.0)}, 5.0), 0.0);
  const cl::ParticleSet copies(4, ct::particle_at(1.0, 2.0, 0.5, 1.0));
  EXPECT_EQ(cl::cloud_pose_blur_m(copies, 5.0), 0.0);
}

TEST(PoseBlur, MedianRangeSkipsReturnsWithoutARange) {
  conicloc::sensor::Scan scan;
  scan.rings.resize(2);
  for (double r : {3.0, 1.0}) scan.rings[0].returns.push_back({.range_m = r});
  scan.rings[1].returns.push_back({.range_m = 2.0});
  scan.rings[1].returns.push_back(
      {.range_m = 0.0, .status = conicloc::sensor::ReturnStatus::NoReturn});
  EXPECT_DOUBLE_EQ(cl::median_range_m(scan), 2.0);
  EXPECT_EQ(cl::median_range_m(conicloc::sensor::Scan{}), 0.0);
}

class BlurredModel : public ::testing::TestWithParam<std::string> {};

// Widening by b ranks a pose b off the truth nearer to it; b within σ (5 cm) gives back the
// configured model bit for bit; the shared part grows with σ, so the scan is worth fewer
// independent terms.
TEST_P(BlurredModel, NarrowsTheGapToANearbyPoseAndZeroRestoresIt) {
  const auto map = ct::make_box_room();
  const cl::Pose3 truth = cl::make_pose(3.0, 2.5, 1.2, 0.4);
  const cl::Pose3 nearby = cl::make_pose(3.3, 2.3, 1.2, 0.45);
  const auto model = ct::model_with_scan(GetParam(), map, truth, 5);
  auto scratch = model->make_scratch();

  const cl::ObservationScore sharp_truth = model->score(truth, scratch.get());
  const cl::ObservationScore sharp_nearby = model->score(nearby, scratch.get());
  const double sharp_terms = model->effective_terms(truth, scratch.get());
  ASSERT_GT(sharp_truth.log_likelihood, sharp_nearby.log_likelihood);

  model->set_pose_blur(0.3);
  const cl::ObservationScore blurred_truth = model->score(truth, scratch.get());
  const cl::ObservationScore blurred_nearby = model->score(nearby, scratch.get());
  EXPECT_LT(blurred_truth.log_likelihood - blurred_nearby.log_likelihood,
            0.5 * (sharp_truth.log_likelihood - sharp_nearby.log_likelihood));
  EXPECT_GT(blurred_nearby.inlier_fraction, sharp_nearby.inlier_fraction);
  EXPECT_LT(model->effective_terms(truth, scratch.get()), sharp_terms);

  model->set_pose_blur(0.04);
  EXPECT_EQ(model->score(truth, scratch.get()).log_likelihood, sharp_truth.log_likelihood);
  EXPECT_EQ(model->score(nearby, scratch.get()).log_likelihood, sharp_nearby.log_likelihood);
  EXPECT_EQ(model->effective_terms(truth, scratch.get()), sharp_terms);
}

INSTANTIATE_TEST_SUITE_P(AllModels, BlurredModel,
                         ::testing::ValuesIn(cl::observation_model_names()));
