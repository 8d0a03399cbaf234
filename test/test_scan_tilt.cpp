// The tilt measured from the scan (localizer/scan_tilt.hpp) and the compass search under it
// (localizer/compass_search.hpp): a scan taken from a tilted sensor gives back its roll and pitch
// with every observation model; the search stays within its bounds and its budget; a pose that
// does not explain the scan measures nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "box_room_scan.hpp"
#include "localizer/filter/compass_search.hpp"
#include "localizer/filter/scan_tilt.hpp"
#include "localizer/models/observation_factory.hpp"

namespace cl = conicloc::localizer;
namespace ct = conicloc::test;

namespace {

constexpr double kDeg = M_PI / 180.0;

}  // namespace

TEST(CompassSearch, ClimbsAQuadraticToWithinItsLastStep) {
  // ℓ(a, b) = −(a − 0.3)² − 4 (b + 0.7)²: peak at (0.3, −0.7).
  double a = 0.0, b = 0.0;
  const auto value = [](double u, double v) {
    return -std::pow(u - 0.3, 2) - 4 * std::pow(v + 0.7, 2);
  };
  const int spent = cl::compass_search(2, 0.25, 0.001, 1000, [&](std::size_t axis, double step) {
    const double u = axis == 0 ? a + step : a;
    const double v = axis == 1 ? b + step : b;
    if (!(value(u, v) > value(a, b))) return cl::Probe::Worse;
    a = u, b = v;
    return cl::Probe::Improved;
  });
  EXPECT_NEAR(a, 0.3, 0.001);
  EXPECT_NEAR(b, -0.7, 0.001);
  EXPECT_GT(spent, 8);
  EXPECT_LT(spent, 1000);
}

TEST(CompassSearch, SkippedProbesCostNothingAndTheBudgetHolds) {
  int evaluated = 0, skipped = 0;
  const int spent = cl::compass_search(3, 1.0, 1e-9, 17, [&](std::size_t axis, double) {
    if (axis == 1) return ++skipped, cl::Probe::Skipped;
    ++evaluated;
    return cl::Probe::Worse;
  });
  EXPECT_EQ(spent, 17);
  EXPECT_EQ(evaluated, 17);
  EXPECT_GT(skipped, 0);
}

class TiltedScan : public ::testing::TestWithParam<std::string> {};

// A scan of the box room from a sensor rolled 1.5° and pitched −2.0°, searched from level at the
// true x, y, z, yaw: every model climbs to its likelihood's peak (as likely as the true tilt, to
// within the search's resolution) and that peak is the sensor's tilt to within 0.3° (the sparser
// models place it by fewer terms: 500 points or a few dozen segments, each a few metres away, with
// 1 cm of range noise; conic-beam lands within 0.05°).
TEST_P(TiltedScan, GivesBackTheSensorsRollAndPitch) {
  const auto map = ct::make_box_room();
  const double roll = 1.5 * kDeg, pitch = -2.0 * kDeg;
  const cl::Pose3 truth = cl::make_pose(3.0, 2.5, 1.2, 0.4, pitch, roll);
  const auto model = ct::model_with_scan(GetParam(), map, truth, 11);
  auto scratch = model->make_scratch();
  int calls = 0;
  const auto score = [&](const cl::PoseState& state) {
    ++calls;
    return model->score(state.to_pose(), scratch.get());
  };

  cl::PoseState level = cl::pose_state_from(truth);
  level.roll = 0.0;
  level.pitch = 0.0;
  cl::ScanTiltConfig tilt_config;
  const auto tilt = cl::measure_tilt(level, 0.0, 0.0, tilt_config, score);
  ASSERT_TRUE(tilt.has_value());
  EXPECT_LE(tilt->evaluations, tilt_config.max_evaluations + 4);
  EXPECT_EQ(calls, tilt->evaluations);
  const double tolerance = (GetParam() == "conic-beam" ? 0.05 : 0.3) * kDeg;
  EXPECT_NEAR(tilt->roll_rad, roll, tolerance);
  EXPECT_NEAR(tilt->pitch_rad, pitch, tolerance);
  // conic-beam's likelihood moves its scan lines' boundaries with the pose (boundary_motion.hpp),
  // so it is continuous where the association cell's edges stood still: its search stops within
  // its last step (min_step_rad, 0.02°) of the peak, 0.0008° from the truth and 0.005 nats below
  // it (0.002 with the mixture instead of its max form), the truth lying nearer the noisy peak.
  // The other models climb past the truth.
  const double slack = GetParam() == "conic-beam" ? 0.01 : 0.0;
  EXPECT_GE(tilt->score.log_likelihood, score(cl::pose_state_from(truth)).log_likelihood - slack);
  EXPECT_GT(tilt->score.log_likelihood, score(level).log_likelihood);
}

INSTANTIATE_TEST_SUITE_P(AllModels, TiltedScan, ::testing::ValuesIn(cl::observation_model_names()));

// The search never leaves max_tilt_rad about the mounting, whatever the likelihood says.
TEST(MeasureTilt, StaysWithinTheMountingsBounds) {
  cl::ScanTiltConfig config;
  config.max_tilt_rad = 1.0 * kDeg;
  config.max_evaluations = 200;
  const double mounting_pitch = 0.5 * kDeg;
  // The likelihood keeps rising towards roll = pitch = 10°.
  const auto score = [](const cl::PoseState& s) {
    return cl::ObservationScore{-std::hypot(s.roll - 10 * kDeg, s.pitch - 10 * kDeg), 0.9};
  };
  const auto tilt = cl::measure_tilt(cl::PoseState{}, 0.0, mounting_pitch, config, score);
  ASSERT_TRUE(tilt.has_value());
  EXPECT_LE(tilt->roll_rad, 1.0 * kDeg + 1e-12);
  EXPECT_LE(tilt->pitch_rad, mounting_pitch + 1.0 * kDeg + 1e-12);
  EXPECT_GT(tilt->roll_rad, 0.9 * kDeg);
}

// A pose that explains too little of the scan (a lost cloud's best particle) measures no tilt;
// neither does a disabled search.
TEST(MeasureTilt, NothingFromAPoseThatDoesNotExplainTheScan) {
  cl::ScanTiltConfig config;
  const auto poor = [](const cl::PoseState& s) {
    return cl::ObservationScore{-std::abs(s.roll), 0.1};
  };
  EXPECT_FALSE(cl::measure_tilt(cl::PoseState{}, 0.0, 0.0, config, poor).has_value());
  const auto good = [](const cl::PoseState& s) {
    return cl::ObservationScore{-std::abs(s.roll), 0.8};
  };
  EXPECT_TRUE(cl::measure_tilt(cl::PoseState{}, 0.0, 0.0, config, good).has_value());
  config.enabled = false;
  EXPECT_FALSE(cl::measure_tilt(cl::PoseState{}, 0.0, 0.0, config, good).has_value());
}

// The curvatures at the peak of a quadratic log-likelihood are its inverse variances, exactly
// (central differences are exact on a parabola).
TEST(MeasureTilt, CurvaturesAreTheInverseVariancesOfAQuadraticPeak) {
  const double sigma_roll = 0.3 * kDeg, sigma_pitch = 0.1 * kDeg;
  const auto score = [&](const cl::PoseState& s) {
    return cl::ObservationScore{-0.5 * std::pow((s.roll - 1.0 * kDeg) / sigma_roll, 2) -
                                    0.5 * std::pow((s.pitch + 0.5 * kDeg) / sigma_pitch, 2),
                                0.9};
  };
  cl::ScanTiltConfig config;
  config.max_evaluations = 200;
  const auto tilt = cl::measure_tilt(cl::PoseState{}, 0.0, 0.0, config, score);
  ASSERT_TRUE(tilt.has_value());
  EXPECT_NEAR(tilt->roll_rad, 1.0 * kDeg, config.min_step_rad);
  EXPECT_NEAR(tilt->pitch_rad, -0.5 * kDeg, config.min_step_rad);
  EXPECT_NEAR(tilt->roll_curvature, 1.0 / (sigma_roll * sigma_roll),
              1e-6 / (sigma_roll * sigma_roll));
  EXPECT_NEAR(tilt->pitch_curvature, 1.0 / (sigma_pitch * sigma_pitch),
              1e-6 / (sigma_pitch * sigma_pitch));
}
