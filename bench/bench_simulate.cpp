// Simulated sensor-seconds per wall-second (counter "x_real_time"); target ≥ 20.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>

#include "io/indoorgml.hpp"
#include "sim/box_building.hpp"
#include "sim/building_generator.hpp"
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

// A generated storeys building of range(0) storeys and range(1) floor plates (issue 15: ≥ 10×
// real time at 10 × 4), range(2) threads; its people walk every storey.
void BM_SimulateScaledBuilding(benchmark::State& state) {
  const conicloc::sim::BuildingScale scale{static_cast<int>(state.range(0)),
                                           static_cast<int>(state.range(1))};
  const auto path = std::filesystem::temp_directory_path() /
                    ("bench_simulate_storeys_" + conicloc::sim::scale_text(scale) + ".gml");
  std::ofstream(path) << conicloc::sim::generate_building_gml("storeys", 1, scale);
  const auto map = conicloc::io::load_indoorgml(path.string(), {}).map;
  std::filesystem::remove(path);
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

}  // namespace

BENCHMARK_MAIN();
