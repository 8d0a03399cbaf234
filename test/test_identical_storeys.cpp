// One scan scores the same at one place on two identical storeys, whatever height the sensor
// stands at: the association grid (association_grid.hpp) must not predict one storey's particles
// from a height nearer to theirs than the other's. With z cells counted from z = 0, a sensor
// 1.33 m above the floor was predicted from 1.25 m on the ground floor and from 4.75 m (0.017 m
// off) one storey up, and a global start settled on the storey whose phase in the grid fitted.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "localizer/models/observation_factory.hpp"
#include "model_test_name.hpp"
#include "synthetic_room.hpp"

namespace cl = conicloc::localizer;
namespace ct = conicloc::test;

namespace {

constexpr double kStorey_m = 3.437;  // floor to floor: 3 m rooms under a slab, off any grid

}  // namespace

class IdenticalStoreys : public ::testing::TestWithParam<std::string> {};

TEST_P(IdenticalStoreys, OneScanScoresTheSameOnBoth) {
  const auto map = ct::make_identical_storeys(kStorey_m);
  cl::ObservationConfig config;
  config.model = GetParam();
  const auto model = cl::make_observation_model(config, map, ct::vlp16());
  auto scratch = model->make_scratch();
  std::mt19937_64 rng(5);
  ct::SyntheticScanOptions options;
  options.range_sigma_m = 0.01;
  // Sensor heights over the floor at different phases of a 0.25 m grid.
  for (const double height : {1.2, 1.33, 1.07, 0.8}) {
    const cl::Pose3 upstairs = cl::make_pose(3.0, 2.5, kStorey_m + height, 0.4);
    const cl::Pose3 downstairs = cl::make_pose(3.0, 2.5, height, 0.4);
    model->prepare(ct::make_scan(map, upstairs, options, rng),
                   Eigen::AlignedBox3d(Eigen::Vector3d(2.0, 1.5, 0.0),
                                       Eigen::Vector3d(4.0, 3.5, 2.0 * kStorey_m)));
    const cl::ObservationScore up = model->score(upstairs, scratch.get());
    const cl::ObservationScore down = model->score(downstairs, scratch.get());
    EXPECT_GT(up.inlier_fraction, 0.95) << "height " << height;
    EXPECT_NEAR(up.log_likelihood, down.log_likelihood, 1e-6 * std::abs(up.log_likelihood))
        << "height " << height;
    EXPECT_NEAR(up.inlier_fraction, down.inlier_fraction, 1e-9) << "height " << height;
  }
}

INSTANTIATE_TEST_SUITE_P(ConicModels, IdenticalStoreys,
                         ::testing::Values("conic-beam", "conic-segment"),
                         conicloc::test::model_test_name);
