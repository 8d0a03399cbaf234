// One weighting pass of the particle filter (every particle scored against one scan), per
// observation model, on one core: the per-scan cost that dominates Localizer::update(); and the
// serial steps before it (de-skew and its re-sort, the turn between scans) on one and two threads.
// Scene: the synthetic box room of the tests (test/synthetic_room.hpp), a full VLP-16 scan at 0.2°.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "localizer/filter/deskew.hpp"
#include "localizer/filter/particle_filter.hpp"
#include "localizer/filter/pose_blur.hpp"
#include "localizer/filter/scan_turn.hpp"
#include "localizer/models/observation_factory.hpp"
#include "sensor/azimuth_order.hpp"
#include "sensor/builtin_calibration.hpp"
#include "test/synthetic_room.hpp"

namespace cl = conicloc::localizer;

namespace {

// conic-beam's variants: the default (beams associated per grid cell, scored in the max-mixture
// form), the mixture itself with one log per chunk of beams (ConicBeamConfig::max_mixture =
// false), and that with a full prediction per particle (PredictionShortcuts::association_grid =
// false: the model before the grid), one log per beam (chunked_log = false), or both (the model
// before either).
enum class BeamVariant {
  kDefault,
  kExactMixture,
  kFullPrediction,
  kPerBeamLog,
  kFullPredictionPerBeamLog
};

// `new_cells`: no prediction kept from the scan before (a cloud that moved into other cells, or
// whose candidates changed); else every cell's prediction is (a tracked cloud meets mostly the
// cells the scan before met). `surface_weights`: the terms raised where a direction's surfaces
// hold few of them, seen from the true pose (ObservationModel::weigh_terms, timed), as a tracking
// Localizer does (LocalizerConfig::surface_weights); the box room's walls are raised.
void BM_WeightParticles(benchmark::State& state, const std::string& model_name,
                        BeamVariant beam_variant = BeamVariant::kDefault,
                        bool share_prediction_across_yaw = true, bool segment_rims = true,
                        bool new_cells = false, bool surface_weights = false) {
  const auto map = conicloc::test::make_box_room();
  const auto calibration =
      conicloc::sensor::builtin_calibration(conicloc::sensor::SensorModel::VLP16);
  cl::ObservationConfig config;
  config.model = model_name;
  config.conic_beam.max_mixture = beam_variant == BeamVariant::kDefault;
  config.shortcuts.association_grid = beam_variant == BeamVariant::kDefault ||
                                      beam_variant == BeamVariant::kExactMixture ||
                                      beam_variant == BeamVariant::kPerBeamLog;
  config.shortcuts.chunked_log = beam_variant != BeamVariant::kPerBeamLog &&
                                 beam_variant != BeamVariant::kFullPredictionPerBeamLog;
  config.shortcuts.share_prediction_across_yaw = share_prediction_across_yaw;
  config.conic_segment.rims = segment_rims;
  const auto model = cl::make_observation_model(config, map, calibration);
  std::mt19937_64 rng(1);
  conicloc::test::SyntheticScanOptions options;
  options.azimuth_step_rad = 0.2 * M_PI / 180.0;
  options.range_sigma_m = 0.03;
  const cl::Pose3 truth = cl::make_pose(3.0, 2.5, 1.2, 0.4);
  const auto scan = conicloc::test::make_scan(map, truth, options, rng);

  cl::FreeSpace free_space(map);
  cl::MotionModel motion(cl::MotionModelConfig{}, free_space);
  cl::ParticleFilter filter(cl::ParticleFilterConfig{}, motion, free_space);
  cl::Vector6 sigma;
  sigma << 0.1, 0.1, 0.01, 0.005, 0.005, 0.03;
  filter.initialise_at(cl::pose_state_from(truth), sigma, static_cast<std::size_t>(state.range(0)),
                       rng);
  model->prepare(scan, filter.position_bounds());
  std::vector<std::unique_ptr<cl::ObservationModel::Scratch>> scratches;
  scratches.push_back(model->make_scratch());  // one worker: one core
  for (auto _ : state) {
    // Every pass is a new scan: the models' per-scan caches (association per grid cell) start
    // empty, as in Localizer::update(); prepare() itself (beam selection, segmentation, culling)
    // is not timed.
    state.PauseTiming();
    // A scan without a cloud has no candidates: the next one's are another version (CloudCull),
    // under which no prediction is kept (their storage is).
    if (new_cells) model->prepare(scan, Eigen::AlignedBox3d());
    model->prepare(scan, filter.position_bounds());
    state.ResumeTiming();
    if (surface_weights) model->weigh_terms(truth, scratches.front().get());
    const auto summary = filter.weight(*model, scratches);
    benchmark::DoNotOptimize(summary);
  }
  state.counters["terms"] = static_cast<double>(model->term_count());
  if (const auto* segments = dynamic_cast<const cl::ConicSegmentModel*>(model.get())) {
    state.counters["segments"] = static_cast<double>(segments->segment_count());
    state.counters["candidates"] =
        static_cast<double>(segments->association_at(truth).terms.size());
  }
  state.counters["particles"] = static_cast<double>(state.range(0));
}

// The pose blur of a spread cloud (pose_blur.hpp: a k-d tree and a nearest-neighbour query per
// particle), paid once per scan while searching; against BM_WeightParticles at the same count.
void BM_CloudPoseBlur(benchmark::State& state) {
  const auto map = conicloc::test::make_box_room();
  cl::FreeSpace free_space(map);
  cl::MotionModel motion(cl::MotionModelConfig{}, free_space);
  cl::ParticleFilter filter(cl::ParticleFilterConfig{}, motion, free_space);
  std::mt19937_64 rng(1);
  filter.initialise_global(static_cast<std::size_t>(state.range(0)), rng);
  for (auto _ : state) benchmark::DoNotOptimize(cl::cloud_pose_blur_m(filter.particles(), 4.0));
  state.counters["particles"] = static_cast<double>(state.range(0));
}

// A searching cloud (a global start in the box room) weighted with conic-beam, with and without
// refining its leading hypotheses (hypothesis_refinement.hpp) at a spacing of 0.2 m: what the
// refinement adds to a searching scan's weighting.
void BM_WeightSearchingCloud(benchmark::State& state, bool refine,
                             std::size_t headings_per_position = 4) {
  const auto map = conicloc::test::make_box_room();
  const auto calibration =
      conicloc::sensor::builtin_calibration(conicloc::sensor::SensorModel::VLP16);
  cl::ObservationConfig config;
  const auto model = cl::make_observation_model(config, map, calibration);
  std::mt19937_64 rng(1);
  conicloc::test::SyntheticScanOptions options;
  options.azimuth_step_rad = 0.2 * M_PI / 180.0;
  options.range_sigma_m = 0.03;
  const auto scan = conicloc::test::make_scan(map, cl::make_pose(3.0, 2.5, 1.2, 0.4), options, rng);
  cl::FreeSpace free_space(map);
  cl::MotionModel motion(cl::MotionModelConfig{}, free_space);
  cl::ParticleFilterConfig filter_config;
  filter_config.headings_per_position = headings_per_position;
  cl::ParticleFilter filter(filter_config, motion, free_space);
  std::vector<std::unique_ptr<cl::ObservationModel::Scratch>> scratches;
  scratches.push_back(model->make_scratch());  // one worker: one core
  const cl::RefinementScale scale{.step_m = refine ? 0.2 : 0.0, .range_m = 4.0};
  for (auto _ : state) {
    state.PauseTiming();
    filter.initialise_global(static_cast<std::size_t>(state.range(0)), rng);
    model->prepare(scan, filter.position_bounds());
    state.ResumeTiming();
    benchmark::DoNotOptimize(filter.weight(*model, scratches, 0.0, scale));
  }
  state.counters["particles"] = static_cast<double>(state.range(0));
}

// The steps of a scan without odometry that precede the weighting, on `state.range(0)` threads:
// de-skewing the scan (one motion per return) and measuring the turn from the range profiles.
// Both work ring by ring (shifts of the turn too), the same result for any thread count.
conicloc::sensor::Scan box_room_scan(const cl::Pose3& pose, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  conicloc::test::SyntheticScanOptions options;
  options.azimuth_step_rad = 0.2 * M_PI / 180.0;
  options.range_sigma_m = 0.03;
  return conicloc::test::make_scan(conicloc::test::make_box_room(), pose, options, rng);
}

void BM_DeskewScan(benchmark::State& state) {
  auto scan = box_room_scan(cl::make_pose(3.0, 2.5, 1.2, 0.4), 1);
  for (auto& ring : scan.rings) {
    for (std::size_t i = 0; i < ring.returns.size(); ++i)
      ring.returns[i].time_s =
          0.1 * static_cast<double>(i) / static_cast<double>(ring.returns.size());
  }
  scan.end_time_s = 0.1;
  const cl::Pose3 motion = cl::make_pose(0.1, 0.02, 0.0, 0.05);
  const int threads = static_cast<int>(state.range(0));
  // range(1) = 1: into one scan kept from call to call, as the localizer does.
  conicloc::sensor::Scan kept;
  for (auto _ : state) {
    if (state.range(1) != 0) {
      cl::deskew_scan_into(scan, motion, 0.1, 0.1, threads, kept);
      benchmark::DoNotOptimize(kept.rings.data());
    } else {
      benchmark::DoNotOptimize(cl::deskew_scan(scan, motion, 0.1, 0.1, threads));
    }
  }
  state.counters["returns"] = static_cast<double>(scan.valid_returns());
}

// The re-sort after de-skew: each ring of a scan turned by a yaw growing over the rotation to
// 0.05 rad (returns moved along the ring, some carried across 2π → 0), copied and sorted by
// std::stable_sort (arg 0, the sort de-skew used before) or sensor::sort_by_azimuth (arg 1); the
// copy is timed in both.
void BM_ResortRings(benchmark::State& state) {
  auto scan = box_room_scan(cl::make_pose(3.0, 2.5, 1.2, 0.4), 1);
  for (auto& ring : scan.rings) {
    for (std::size_t i = 0; i < ring.returns.size(); ++i) {
      auto& azimuth = ring.returns[i].azimuth_rad;
      azimuth = std::fmod(
          azimuth + 0.05 * static_cast<double>(i) / static_cast<double>(ring.returns.size()),
          2.0 * M_PI);
    }
  }
  const bool near_order = state.range(0) == 1;
  for (auto _ : state) {
    for (const auto& ring : scan.rings) {
      std::vector<conicloc::sensor::Return> returns = ring.returns;
      if (near_order) {
        conicloc::sensor::sort_by_azimuth(returns);
      } else {
        std::stable_sort(returns.begin(), returns.end(), [](const auto& a, const auto& b) {
          return a.azimuth_rad < b.azimuth_rad;
        });
      }
      benchmark::DoNotOptimize(returns.data());
    }
  }
}

void BM_ScanTurn(benchmark::State& state) {
  const cl::Pose3 a = cl::make_pose(3.0, 2.5, 1.2, 0.4);
  const auto first = box_room_scan(a, 1);
  const auto second = box_room_scan(a * cl::make_pose(0.08, 0.0, 0.0, 0.05), 2);
  cl::ScanTurn turn({}, static_cast<int>(state.range(0)));
  for (auto _ : state) {
    state.PauseTiming();
    turn.reset();
    turn.update(first, Eigen::Vector2d(0.08, 0.0));
    state.ResumeTiming();
    benchmark::DoNotOptimize(turn.update(second, Eigen::Vector2d(0.08, 0.0)));
  }
}

}  // namespace

BENCHMARK(BM_DeskewScan)
    ->Args({1, 0})
    ->Args({1, 1})
    ->Args({2, 0})
    ->Args({2, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_ResortRings)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ScanTurn)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_WeightSearchingCloud, one_heading_per_position, false, 1)
    ->Arg(1000)
    ->Arg(5000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_WeightSearchingCloud, plain, false)
    ->Arg(1000)
    ->Arg(5000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_WeightSearchingCloud, refined, true)
    ->Arg(1000)
    ->Arg(5000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CloudPoseBlur)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_WeightParticles, conic_beam, std::string("conic-beam"))
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond);
// Baseline of the same run: the mixture itself, an exp per beam (the default before the max form).
BENCHMARK_CAPTURE(BM_WeightParticles, conic_beam_exact_mixture, std::string("conic-beam"),
                  BeamVariant::kExactMixture)
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond);
// Raised terms: BeamLikelihoodSum::weighted_max_sum, no exp or log per beam.
BENCHMARK_CAPTURE(BM_WeightParticles, conic_beam_surface_weights, std::string("conic-beam"),
                  BeamVariant::kDefault, true, true, false, true)
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond);
// Baseline of the same run: every cell predicted anew, as in the first scan that meets it.
BENCHMARK_CAPTURE(BM_WeightParticles, conic_beam_new_cells, std::string("conic-beam"),
                  BeamVariant::kDefault, true, true, true)
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_WeightParticles, conic_beam_full_prediction, std::string("conic-beam"),
                  BeamVariant::kFullPrediction)
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_WeightParticles, conic_beam_per_beam_log, std::string("conic-beam"),
                  BeamVariant::kPerBeamLog)
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_WeightParticles, conic_beam_full_prediction_per_beam_log,
                  std::string("conic-beam"), BeamVariant::kFullPredictionPerBeamLog)
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_WeightParticles, conic_segment, std::string("conic-segment"))
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_WeightParticles, conic_segment_surface_weights, std::string("conic-segment"),
                  BeamVariant::kDefault, true, true, false, true)
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_WeightParticles, conic_segment_new_cells, std::string("conic-segment"),
                  BeamVariant::kDefault, true, true, true)
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond);
// Baseline of conic_segment_new_cells: every association cell predicted at its centre, none
// turned.
BENCHMARK_CAPTURE(BM_WeightParticles, conic_segment_no_yaw_sharing, std::string("conic-segment"),
                  BeamVariant::kDefault, false, true, true)
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond);
// Baseline of the same run: each segment compared with its polygon's plane only, no rims.
BENCHMARK_CAPTURE(BM_WeightParticles, conic_segment_planes_only, std::string("conic-segment"),
                  BeamVariant::kDefault, true, false)
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_WeightParticles, point_to_plane, std::string("point-to-plane"))
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
