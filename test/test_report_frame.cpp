// The sampled frames of `conicloc report` (eval/report_frame.hpp) and the reader of the details
// CSV it draws its plots from (eval/details_csv_reader.hpp).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "eval/details_csv_reader.hpp"
#include "eval/report_frame.hpp"
#include "io/input_error.hpp"
#include "synthetic_room.hpp"

namespace conicloc {
namespace {

TEST(ReportFrame, SamplingStrideKeepsAtMostTheLimit) {
  EXPECT_EQ(eval::sampling_stride(0, 600), 1u);
  EXPECT_EQ(eval::sampling_stride(600, 600), 1u);
  EXPECT_EQ(eval::sampling_stride(601, 600), 2u);
  EXPECT_EQ(eval::sampling_stride(3600, 600), 6u);
  EXPECT_EQ(eval::sampling_stride(3601, 600), 7u);
  EXPECT_EQ(eval::sampling_stride(5000, 0), 1u);
  for (const std::size_t count : {1u, 599u, 1000u, 3599u, 36001u}) {
    const std::size_t stride = eval::sampling_stride(count, 600);
    EXPECT_LE((count + stride - 1) / stride, 600u) << count;
  }
}

TEST(ReportFrame, PredictedRangesAreTheConicModelsAtTheEstimate) {
  const maps::PlaneMap map = test::make_box_room();
  const localizer::ConicScanPredictor predictor(map, test::vlp16());
  const localizer::Pose3 pose = localizer::make_pose(3.0, 2.5, 0.8, 0.4);
  std::mt19937_64 rng(7);
  const sensor::Scan scan = test::make_scan(map, pose, {}, rng);
  const eval::ReportFrameLimits limits;
  const auto frame = eval::make_report_frame(12.5, 3, pose, scan, nullptr, predictor, limits);

  localizer::PredictedScan predicted;
  predictor.predict(pose, predicted);
  ASSERT_EQ(frame.predicted.size(), 16u);
  const std::size_t samples =
      static_cast<std::size_t>(std::ceil(2.0 * std::numbers::pi / limits.conic_step_rad - 1e-9));
  for (std::size_t k = 0; k < frame.predicted.size(); ++k) {
    ASSERT_EQ(frame.predicted[k].size(), samples);
    for (std::size_t i = 0; i < samples; ++i) {
      const double expected =
          predicted.rings[k].range(static_cast<double>(i) * limits.conic_step_rad);
      EXPECT_NEAR(frame.predicted[k][i], std::isfinite(expected) ? expected : 0.0, 1e-9);
    }
  }
  // Inside a closed room every ring sees a wall at every azimuth (downward rings the floor).
  for (const auto& ring : frame.predicted)
    for (const double range : ring) EXPECT_GT(range, 0.0);
  EXPECT_TRUE(frame.particles.empty());
  EXPECT_EQ(frame.particle_count, 0u);
  EXPECT_EQ(frame.scan, 3u);
  EXPECT_DOUBLE_EQ(frame.time_s, 12.5);
}

TEST(ReportFrame, MeasuredReturnsAndParticlesAreEvenSubsamples) {
  const maps::PlaneMap map = test::make_box_room();
  const localizer::ConicScanPredictor predictor(map, test::vlp16());
  const localizer::Pose3 pose = localizer::make_pose(5.0, 3.0, 0.8, -1.0);
  std::mt19937_64 rng(3);
  sensor::Scan scan = test::make_scan(map, pose, {}, rng);
  scan.rings[5].returns[0].status = sensor::ReturnStatus::NoReturn;  // never drawn
  localizer::ParticleSet particles(1000);
  for (std::size_t i = 0; i < particles.size(); ++i) particles[i].state.x = static_cast<double>(i);
  eval::ReportFrameLimits limits;
  limits.max_particles = 300;
  limits.points_per_ring = 32;
  const auto frame = eval::make_report_frame(0.0, 0, pose, scan, &particles, predictor, limits);

  EXPECT_EQ(frame.particle_count, 1000u);
  ASSERT_EQ(frame.particles.size(), 250u);  // stride ⌈1000 / 300⌉ = 4
  for (std::size_t i = 0; i < frame.particles.size(); ++i)
    EXPECT_EQ(frame.particles[i].x, static_cast<double>(4 * i));
  ASSERT_EQ(frame.measured.size(), scan.rings.size());
  for (std::size_t k = 0; k < scan.rings.size(); ++k) {
    std::vector<std::pair<double, double>> valid;
    for (const auto& ret : scan.rings[k].returns)
      if (ret.status == sensor::ReturnStatus::Valid)
        valid.emplace_back(ret.azimuth_rad, ret.range_m);
    ASSERT_FALSE(valid.empty());
    const std::size_t stride = eval::sampling_stride(valid.size(), 32);
    ASSERT_EQ(frame.measured[k].size(), (valid.size() + stride - 1) / stride) << k;
    EXPECT_LE(frame.measured[k].size(), 32u);
    for (std::size_t i = 0; i < frame.measured[k].size(); ++i)
      EXPECT_EQ(frame.measured[k][i], valid[i * stride]);
  }
}

constexpr const char* kDetailsHeader =
    "time_s,x,y,z,qx,qy,qz,qw,particles,time_ms,recovered,spread_m,status,extra\n";

TEST(DetailsCsvReader, ReadsTheColumnsByName) {
  const double half = std::sqrt(0.5);
  const std::string text = std::string(kDetailsHeader) +
                           "100.5,1.5,-2,0.8,0,0,0,1,500,12.5,0,0.05,tracking,x\n" +
                           "100.6,1.6,-2.1,0.8,0,0," + std::to_string(half) + "," +
                           std::to_string(half) + ",2000,30,1,3.5,lost,y\n";
  const auto rows = eval::read_details_csv(text, "d.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_DOUBLE_EQ(rows[0].time_s, 100.5);
  EXPECT_DOUBLE_EQ(rows[0].T_map_sensor.translation().x(), 1.5);
  EXPECT_DOUBLE_EQ(rows[0].particles, 500);
  EXPECT_DOUBLE_EQ(rows[0].time_ms, 12.5);
  EXPECT_FALSE(rows[0].recovered);
  EXPECT_EQ(rows[0].status, "tracking");
  EXPECT_TRUE(rows[1].recovered);
  EXPECT_EQ(rows[1].status, "lost");
  EXPECT_NEAR(localizer::yaw_of(rows[1].T_map_sensor), std::numbers::pi / 2, 1e-6);
}

std::string error_of(const std::string& text) {
  try {
    eval::read_details_csv(text, "run/details.csv");
  } catch (const io::InputError& e) {
    return e.what();
  }
  return "";
}

TEST(DetailsCsvReader, NamesFileAndLineOfABadRow) {
  EXPECT_THAT(error_of("time_s,x,y\n1,2,3\n"),
              testing::AllOf(testing::HasSubstr("run/details.csv"), testing::HasSubstr("line 1"),
                             testing::HasSubstr("'z'")));
  const std::string good = "1,1,2,0.8,0,0,0,1,500,12.5,0,0.05,tracking,x\n";
  EXPECT_THAT(error_of(kDetailsHeader + good + "2,1,2,0.8,0,0,0,1,500\n"),
              testing::AllOf(testing::HasSubstr("run/details.csv"), testing::HasSubstr("line 3"),
                             testing::HasSubstr("9 fields")));
  EXPECT_THAT(error_of(kDetailsHeader + good + good + "3,1,2,0.8,0,0,0,1,many,1,0,0,lost,x\n"),
              testing::AllOf(testing::HasSubstr("line 4"), testing::HasSubstr("particles 'many'")));
  EXPECT_THAT(error_of(kDetailsHeader + std::string("3,1,2,0.8,0,0,0,0,1,1,0,0,lost,x\n")),
              testing::AllOf(testing::HasSubstr("line 2"), testing::HasSubstr("quaternion")));
}

}  // namespace
}  // namespace conicloc
