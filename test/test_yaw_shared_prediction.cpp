// Level association cells share one prediction, turned in azimuth (localizer/
// yaw_shared_prediction.hpp): the turned scan is the scan predicted at the turned pose (same
// surfaces, same ranges), turn_ring is right at awkward yaws, a prediction is kept for the next
// scan while its candidates and rings stay, and the conic models score particles the same with
// and without sharing, and with predictions kept or made anew.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <numeric>
#include <random>

#include "io/indoorgml.hpp"
#include "localizer/conic/yaw_shared_prediction.hpp"
#include "localizer/models/observation_factory.hpp"
#include "test/predicted_scan_compare.hpp"
#include "test/shared_buildings.hpp"
#include "test/synthetic_room.hpp"

namespace cl = conicloc::localizer;
namespace ct = conicloc::test;

namespace {

constexpr double kAngle = 2.0 * std::numbers::pi / 180.0;
const cl::AssociationGrid kGrid({0.25, 0.25, kAngle});

std::vector<int> every_polygon(const conicloc::maps::PlaneMap& map) {
  std::vector<int> all(map.polygons.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  return all;
}

cl::AssociationCellKey cell_at(const Eigen::Vector3d& p, int yaw_bin, int pitch_bin) {
  return kGrid.cell_of(cl::make_pose(p.x(), p.y(), p.z(), yaw_bin * kAngle, pitch_bin * kAngle));
}

}  // namespace

namespace {

// Turned scans equal direct predictions at the level centres of random positions in the map's
// bounds (yaw bins 0, 1, −7, 45, 89, −89, −45), and tilted centres are predicted directly.
// Returns the number of azimuths compared.
int expect_turned_scans_are_direct_ones(const conicloc::maps::PlaneMap& map, int positions,
                                        unsigned seed) {
  const cl::ConicScanPredictor predictor(map, ct::vlp16(), {});
  const std::vector<int> all = every_polygon(map);
  std::vector<int> rings(predictor.rings().size());
  std::iota(rings.begin(), rings.end(), 0);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::AlignedBox3d& box = map.bounds;
  cl::YawSharedPrediction shared;
  cl::PredictedScan turned, direct;
  int compared = 0, turned_count = 0;
  for (int position = 0; position < positions; ++position) {
    const Eigen::Vector3d p =
        box.min() +
        (box.max() - box.min()).cwiseProduct(Eigen::Vector3d(unit(rng), unit(rng), unit(rng)));
    for (const int yaw_bin : {0, 1, -7, 45, 89, -89, -45}) {
      for (const int pitch_bin : {0, 1}) {
        const cl::AssociationCellKey cell = cell_at(p, yaw_bin, pitch_bin);
        const bool was_turned =
            shared.predict(predictor, cell, all, 1, rings, 1, kGrid, true, turned);
        EXPECT_EQ(was_turned, pitch_bin == 0);  // level centres are turned, tilted ones not
        turned_count += was_turned ? 1 : 0;
        predictor.predict(kGrid.centre(cell), all, direct);
        compared += ct::expect_same_scans(
            turned, direct, 1e-9,
            "position " + std::to_string(position) + " yaw bin " + std::to_string(yaw_bin), &map);
      }
    }
  }
  EXPECT_EQ(turned_count, positions * 7);
  return compared;
}

}  // namespace

TEST(YawSharedPrediction, ALevelPredictionTurnedInAzimuthIsThePredictionAtThatYaw) {
  const auto map = conicloc::io::load_indoorgml(CONICLOC_EXAMPLE_MAP).map;
  EXPECT_GT(expect_turned_scans_are_direct_ones(map, 12, 6), 1000000);
}

TEST(YawSharedPrediction, TurnedScansAreDirectOnesOnThePublicBuildings) {
  const auto models = ct::shared_indoorgml_models();
  if (models.empty()) GTEST_SKIP() << "shared data absent: " << ct::shared_indoorgml_dir();
  for (const auto& path : models) {
    SCOPED_TRACE(path.filename().string());
    const auto map = conicloc::io::load_indoorgml(path.string()).map;
    EXPECT_GT(expect_turned_scans_are_direct_ones(map, 3, 8), 100000);
  }
  EXPECT_GE(models.size(), 4u);
}

TEST(YawSharedPrediction, TurnRingHandlesYawsAtTheWrapAndOnBoundaries) {
  cl::PredictedRing ring;  // three surfaces over [0, 1), [1, 4), [4, 2π)
  ring.clear();
  const double two_pi = 2.0 * std::numbers::pi;
  const double ends[] = {1.0, 4.0, two_pi};
  for (int i = 0; i < 3; ++i) {
    ring.a.push_back(0.1 * (i + 1));
    ring.b.push_back(-0.05 * i);
    ring.c.push_back(0.3);
    ring.polygon.push_back(i);
    ring.boundary_rad.push_back(ends[i]);
  }
  for (const double yaw : {-1e-17, 0.0, -0.0, 1.0, 4.0, two_pi, -two_pi, 1e-17, 2.5, -2.5, 7.0}) {
    cl::PredictedRing out;
    cl::turn_ring(ring, yaw, out);
    ASSERT_GE(out.piece_count(), 3u) << yaw;
    EXPECT_EQ(out.boundary_rad.front(), 0.0) << yaw;
    EXPECT_EQ(out.boundary_rad.back(), two_pi) << yaw;
    for (std::size_t i = 0; i < out.piece_count(); ++i) {
      EXPECT_LE(out.boundary_rad[i], out.boundary_rad[i + 1]) << yaw;
    }
    for (int s = 0; s < 3600; ++s) {
      const double theta = two_pi * (s + 0.5) / 3600;
      const std::size_t turned = out.piece_at(theta), original = ring.piece_at(theta + yaw);
      EXPECT_EQ(out.polygon[turned], ring.polygon[original]) << yaw << " " << theta;
      const double expected = ring.a[original] * std::cos(theta + yaw) +
                              ring.b[original] * std::sin(theta + yaw) + ring.c[original];
      const double got =
          out.a[turned] * std::cos(theta) + out.b[turned] * std::sin(theta) + out.c[turned];
      EXPECT_NEAR(got, expected, 1e-12) << yaw << " " << theta;
    }
  }
}

// Some rings only (a searching cloud's scan): the turned scan is the direct prediction of those
// rings, and a new scan with other rings is not served the old ones.
TEST(YawSharedPrediction, TurnsTheRingsAskedFor) {
  const auto map = conicloc::io::load_indoorgml(CONICLOC_EXAMPLE_MAP).map;
  const cl::ConicScanPredictor predictor(map, ct::vlp16(), {});
  const std::vector<int> all = every_polygon(map), some = {2, 6, 10, 14}, others = {1, 5};
  const std::vector<int> kOneGap = {-1};
  cl::YawSharedPrediction shared;
  cl::PredictedScan turned, direct;
  for (const int yaw_bin : {0, 33, -71}) {
    const cl::AssociationCellKey cell = cell_at(map.bounds.center(), yaw_bin, 0);
    ASSERT_TRUE(shared.predict(predictor, cell, all, 1, some, 1, kGrid, true, turned));
    predictor.predict(kGrid.centre(cell), all, some, direct);
    ct::expect_same_scans(turned, direct, 1e-9, "yaw bin " + std::to_string(yaw_bin), &map);
    EXPECT_NE(turned.rings[6].polygon, kOneGap);  // a ring asked for sees the building
    EXPECT_EQ(turned.rings[5].polygon, kOneGap);  // one not asked for is one gap
  }
  const cl::AssociationCellKey cell = cell_at(map.bounds.center(), 0, 0);
  ASSERT_TRUE(shared.predict(predictor, cell, all, 1, others, 2, kGrid, true, turned));
  EXPECT_NE(turned.rings[5].polygon, kOneGap);
  EXPECT_EQ(turned.rings[6].polygon, kOneGap);
}

TEST(YawSharedPrediction, ACellsPredictorKeepsSurfacesOutToItsRangeMargin) {
  const cl::AssociationCellSize cell;  // 0.25 m, 2°
  EXPECT_NEAR(cell.range_margin_m(100.0), cell.half_diagonal_m() + 100.0 * 0.0349066, 1e-12);
  EXPECT_NEAR(cl::cell_predictor_config({}, cell, 100.0).beyond_range_margin_m,
              cell.range_margin_m(100.0), 1e-12);
  // A larger margin set by hand is kept.
  EXPECT_EQ(
      cl::cell_predictor_config({.beyond_range_margin_m = 9.0}, cell, 100.0).beyond_range_margin_m,
      9.0);
}

// A cell's prediction is kept for the scan after the one that met it, and forgotten once a scan
// passes without it. Candidates left out on purpose (none, under the same version) show which
// prediction is handed back.
TEST(YawSharedPrediction, APredictionIsKeptForTheScanAfterTheOneThatMetIt) {
  const auto map = conicloc::io::load_indoorgml(CONICLOC_EXAMPLE_MAP).map;
  const cl::ConicScanPredictor predictor(map, ct::vlp16(), {});
  const std::vector<int> all = every_polygon(map), none;
  std::vector<int> rings(predictor.rings().size());
  std::iota(rings.begin(), rings.end(), 0);
  const Eigen::Vector3d middle = map.bounds.center();
  for (const int pitch_bin : {0, 1}) {  // turned from a level prediction, and predicted directly
    SCOPED_TRACE("pitch bin " + std::to_string(pitch_bin));
    const cl::AssociationCellKey cell = cell_at(middle, 10, pitch_bin);
    const cl::AssociationCellKey elsewhere =
        cell_at(middle + Eigen::Vector3d(1.0, 0.0, 0.0), 10, pitch_bin);
    cl::YawSharedPrediction shared;
    cl::PredictedScan first, kept, other, forgotten;
    shared.predict(predictor, cell, all, 1, rings, 1, kGrid, true, first);
    shared.predict(predictor, cell, none, 1, rings, 2, kGrid, true, kept);
    ct::expect_same_scans(kept, first, 0.0, "the scan after");
    shared.predict(predictor, elsewhere, all, 1, rings, 3, kGrid, true, other);
    shared.predict(predictor, cell, none, 1, rings, 4, kGrid, true, forgotten);
    std::size_t pieces_seen = 0;
    for (const auto& ring : first.rings) {
      for (const int polygon : ring.polygon) pieces_seen += polygon >= 0 ? 1 : 0;
    }
    EXPECT_GT(pieces_seen, 0u);
    for (const auto& ring : forgotten.rings) {
      for (const int polygon : ring.polygon) EXPECT_EQ(polygon, -1);
    }
  }
}

// Other candidates (another version) or other rings than the last call's (a searching cloud scores
// four) forget what was kept.
TEST(YawSharedPrediction, OtherCandidatesOrRingsForgetTheKeptPredictions) {
  const auto map = conicloc::io::load_indoorgml(CONICLOC_EXAMPLE_MAP).map;
  const cl::ConicScanPredictor predictor(map, ct::vlp16(), {});
  const std::vector<int> all = every_polygon(map), none;
  const std::vector<int> every_ring = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
  const std::vector<int> four = {0, 5, 10, 15};
  const cl::AssociationCellKey cell = cell_at(map.bounds.center(), 10, 0);
  cl::YawSharedPrediction shared;
  cl::PredictedScan scan;
  shared.predict(predictor, cell, all, 1, every_ring, 1, kGrid, true, scan);
  shared.predict(predictor, cell, none, 1, four, 1, kGrid, true, scan);
  for (const auto& ring : scan.rings) {
    for (const int polygon : ring.polygon) EXPECT_EQ(polygon, -1);
  }
  shared.predict(predictor, cell, all, 1, every_ring, 2, kGrid, true, scan);
  shared.predict(predictor, cell, none, 2, every_ring, 2, kGrid, true, scan);
  for (const auto& ring : scan.rings) {
    for (const int polygon : ring.polygon) EXPECT_EQ(polygon, -1);
  }
}

TEST(YawSharedPrediction, ConicModelsScoreParticlesTheSameWithAndWithoutSharing) {
  const auto map = ct::make_box_room();
  std::mt19937_64 rng(3);
  ct::SyntheticScanOptions options;
  options.azimuth_step_rad = 0.4 * std::numbers::pi / 180.0;
  options.range_sigma_m = 0.02;
  const cl::Pose3 truth = cl::make_pose(3.0, 2.5, 1.2, 0.4);
  const auto scan = ct::make_scan(map, truth, options, rng);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<cl::Pose3> particles;
  for (int i = 0; i < 300; ++i) {
    particles.push_back(cl::make_pose(3.0 + 0.2 * noise(rng), 2.5 + 0.2 * noise(rng),
                                      1.2 + 0.01 * noise(rng), 0.4 + 0.1 * noise(rng),
                                      0.003 * noise(rng), 0.003 * noise(rng)));
  }
  Eigen::AlignedBox3d cloud;
  for (const auto& pose : particles) cloud.extend(Eigen::Vector3d(pose.translation()));
  for (const std::string model_name : {"conic-beam", "conic-segment"}) {
    cl::ObservationConfig shared_config, direct_config;
    shared_config.model = direct_config.model = model_name;
    direct_config.shortcuts.share_prediction_across_yaw = false;
    const auto shared = cl::make_observation_model(shared_config, map, ct::vlp16());
    const auto direct = cl::make_observation_model(direct_config, map, ct::vlp16());
    shared->prepare(scan, cloud);
    direct->prepare(scan, cloud);
    const auto shared_scratch = shared->make_scratch();
    const auto direct_scratch = direct->make_scratch();
    for (std::size_t i = 0; i < particles.size(); ++i) {
      const auto a = shared->score(particles[i], shared_scratch.get());
      const auto b = direct->score(particles[i], direct_scratch.get());
      EXPECT_NEAR(a.log_likelihood, b.log_likelihood, 1e-9 * std::abs(b.log_likelihood))
          << model_name << " particle " << i;
      EXPECT_NEAR(a.inlier_fraction, b.inlier_fraction, 1e-12) << model_name << " particle " << i;
    }
  }
}

// A prediction kept from the scan before, made by another thread's scratch, scores a particle bit
// for bit as one made anew: two scans of a moving sensor, the second cloud within the first's
// culled region (CloudCull keeps the candidates), scored with the two scratches swapped against a
// model that saw the same clouds but scores the second scan with a fresh scratch.
TEST(YawSharedPrediction, ConicModelsScoreTheSameWithPredictionsKeptOrMadeAnew) {
  const auto map = ct::make_box_room();
  const cl::Pose3 first_truth = cl::make_pose(3.0, 2.5, 1.2, 0.4);
  const cl::Pose3 second_truth = cl::make_pose(3.08, 2.53, 1.2, 0.42);
  const double step_rad = 0.4 * std::numbers::pi / 180.0;
  const auto first_scan = ct::make_scan(map, first_truth, step_rad, 0.02, 8);
  const auto second_scan = ct::make_scan(map, second_truth, step_rad, 0.02, 9);
  std::mt19937_64 rng(8);
  std::normal_distribution<double> noise(0.0, 1.0);
  const auto cloud_about = [&](const cl::Pose3& truth) {
    std::vector<cl::Pose3> particles;
    const Eigen::Vector3d t = truth.translation();
    const double yaw = std::atan2(truth.linear()(1, 0), truth.linear()(0, 0));
    for (int i = 0; i < 200; ++i) {
      particles.push_back(cl::make_pose(t.x() + 0.1 * noise(rng), t.y() + 0.1 * noise(rng),
                                        t.z() + 0.01 * noise(rng), yaw + 0.05 * noise(rng),
                                        0.01 * noise(rng), 0.01 * noise(rng)));
    }
    return particles;
  };
  const auto box_of = [](const std::vector<cl::Pose3>& particles) {
    Eigen::AlignedBox3d box;
    for (const auto& pose : particles) box.extend(Eigen::Vector3d(pose.translation()));
    return box;
  };
  const std::vector<cl::Pose3> first = cloud_about(first_truth);
  const std::vector<cl::Pose3> second = cloud_about(second_truth);
  for (const std::string model_name : {"conic-beam", "conic-segment"}) {
    SCOPED_TRACE(model_name);
    cl::ObservationConfig config;
    config.model = model_name;
    const auto kept = cl::make_observation_model(config, map, ct::vlp16());
    const auto anew = cl::make_observation_model(config, map, ct::vlp16());
    const auto scratch_a = kept->make_scratch();
    const auto scratch_b = kept->make_scratch();
    kept->prepare(first_scan, box_of(first));
    anew->prepare(first_scan, box_of(first));
    for (std::size_t i = 0; i < first.size(); ++i) {
      kept->score(first[i], i % 2 == 0 ? scratch_a.get() : scratch_b.get());
    }
    kept->prepare(second_scan, box_of(second));
    anew->prepare(second_scan, box_of(second));
    const auto fresh = anew->make_scratch();
    for (std::size_t i = 0; i < second.size(); ++i) {
      const auto a = kept->score(second[i], i % 2 == 0 ? scratch_b.get() : scratch_a.get());
      const auto b = anew->score(second[i], fresh.get());
      EXPECT_EQ(a.log_likelihood, b.log_likelihood) << "particle " << i;
      EXPECT_EQ(a.inlier_fraction, b.inlier_fraction) << "particle " << i;
    }
  }
}
