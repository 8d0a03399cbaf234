// Simulated sensor-seconds per wall-second (counter "x_real_time"; target ≥ 20), and the cost of
// a firing's map casts per ray, alone against shared (CastFirings).
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "io/indoorgml.hpp"
#include "sim/box_building.hpp"
#include "sim/building_generator.hpp"
#include "sim/polygon_bvh.hpp"
#include "sim/simulation.hpp"

namespace {

using conicloc::sim::Simulation;
using conicloc::sim::SimulationConfig;

void run_simulation(benchmark::State& state, const conicloc::maps::PlaneMap& map) {
  SimulationConfig config;  // every effect on, clutter level 1
  config.duration_s = 2.0;
  config.threads = static_cast<int>(state.range(0));
  config.sensor.dual_return = state.range(1) != 0;
  Simulation simulation(map, config);
  std::size_t packets = 0;
  for (auto _ : state) {
    const auto stats = simulation.run([&](const auto&, double) { ++packets; });
    benchmark::DoNotOptimize(stats.sensor.rays);
  }
  state.counters["x_real_time"] = benchmark::Counter(
      config.duration_s * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["packets"] =
      static_cast<double>(packets) / static_cast<double>(state.iterations());
}

void BM_SimulateBoxBuilding(benchmark::State& state) {
  run_simulation(state, conicloc::sim::make_box_building());
}
BENCHMARK(BM_SimulateBoxBuilding)
    ->Args({1, 0})
    ->Args({2, 0})
    ->Args({1, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_SimulateExampleBuilding(benchmark::State& state) {
  if (!std::filesystem::exists(CONICLOC_EXAMPLE_MAP)) {
    state.SkipWithError("example building missing");
    return;
  }
  static const auto map = conicloc::io::load_indoorgml(CONICLOC_EXAMPLE_MAP, {}).map;
  run_simulation(state, map);
}
BENCHMARK(BM_SimulateExampleBuilding)
    ->Args({1, 0})
    ->Args({2, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The generated storeys building (seed 1) of range(0) storeys and range(1) floor plates, loaded
// as `conicloc simulate --map` would.
conicloc::maps::PlaneMap storeys_building(const benchmark::State& state) {
  const conicloc::sim::BuildingScale scale{static_cast<int>(state.range(0)),
                                           static_cast<int>(state.range(1))};
  const auto path = std::filesystem::temp_directory_path() /
                    ("bench_simulate_storeys_" + conicloc::sim::scale_text(scale) + ".gml");
  std::ofstream(path) << conicloc::sim::generate_building_gml("storeys", 1, scale);
  auto map = conicloc::io::load_indoorgml(path.string(), {}).map;
  std::filesystem::remove(path);
  return map;
}

// A generated storeys building of range(0) storeys and range(1) floor plates (issue 15: ≥ 10×
// real time at 10 × 4), range(2) threads; its people walk every storey.
void BM_SimulateScaledBuilding(benchmark::State& state) {
  const auto map = storeys_building(state);
  SimulationConfig config;
  config.duration_s = 2.0;
  config.threads = static_cast<int>(state.range(2));
  Simulation simulation(map, config);
  for (auto _ : state) {
    const auto stats = simulation.run([](const auto&, double) {});
    benchmark::DoNotOptimize(stats.sensor.rays);
  }
  state.counters["x_real_time"] = benchmark::Counter(
      config.duration_s * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["people"] = static_cast<double>(simulation.world().people().size());
}
BENCHMARK(BM_SimulateScaledBuilding)
    ->Args({1, 1, 1})
    ->Args({10, 4, 1})
    ->Args({10, 4, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The map-surface casts of 2 s of firings along the simulated trajectory in a generated storeys
// building of range(0) storeys and range(1) floor plates, one thread, hinted with each laser's
// last hit as the simulator does: range(2) = 0 each ray descends the polygon tree alone
// (PolygonBvh::nearest_hit, the baseline), 1 the firing's 16 rays share it (nearest_hits).
void BM_CastFirings(benchmark::State& state) {
  using conicloc::sim::PolygonBvh;
  using conicloc::sim::PolygonHit;
  using conicloc::sim::Ray;
  const auto map = storeys_building(state);
  SimulationConfig config;
  config.duration_s = 2.0;
  const Simulation simulation(map, config);
  const PolygonBvh bvh(simulation.world().polygons());
  const auto& lasers = simulation.sensor().true_calibration().lasers;
  constexpr double kSequencePeriod_s = 55.296e-6;  // VLP-16 manual: one firing sequence
  std::vector<std::array<Ray, 16>> firings;
  for (double t = 0.0; t < config.duration_s; t += kSequencePeriod_s) {
    const Eigen::Isometry3d pose = simulation.trajectory().T_map_sensor(t);
    const double azimuth = simulation.sensor().azimuth_at(t);
    std::array<Ray, 16>& rays = firings.emplace_back();
    for (int k = 0; k < 16; ++k) {
      const double elevation = lasers[k].elevation_rad;
      rays[k].origin = pose * Eigen::Vector3d(0.0, 0.0, lasers[k].vertical_offset_m);
      rays[k].direction = pose.linear() * Eigen::Vector3d(std::cos(elevation) * std::cos(azimuth),
                                                          std::cos(elevation) * std::sin(azimuth),
                                                          std::sin(elevation));
    }
  }
  const bool fan = state.range(2) != 0;
  std::array<int, 16> hints;
  std::array<std::optional<PolygonHit>, 16> hits;
  for (auto _ : state) {
    hints.fill(-1);
    for (const auto& rays : firings) {
      if (fan) {
        bvh.nearest_hits(rays, 0.0, 101.0, hints, hits);
      } else {
        for (int k = 0; k < 16; ++k) hits[k] = bvh.nearest_hit(rays[k], 0.0, 101.0, hints[k]);
      }
      for (int k = 0; k < 16; ++k) {
        if (hits[k]) hints[k] = hits[k]->polygon;
      }
      benchmark::DoNotOptimize(hits);
    }
  }
  state.counters["per_ray"] = benchmark::Counter(
      static_cast<double>(16 * firings.size()) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["polygons"] = static_cast<double>(bvh.polygons().size());
}
BENCHMARK(BM_CastFirings)
    ->Args({1, 1, 0})
    ->Args({1, 1, 1})
    ->Args({10, 4, 0})
    ->Args({10, 4, 1})
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
