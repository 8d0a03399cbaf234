// The plan search of a global start (localizer/filter/plan_search.hpp) against floor area: a
// floor of n × n box rooms (10 m × 6 m each, a pillar placed at random in every room, so that
// they differ; 32 × 32 rooms are PNU's 60,000 m²), one scan from the first room.
// BM_BuildPlanFields: the fields' precomputation, once per start; BM_PlanSearch: one search, with
// the scan's proposed headings (four, as a Manhattan building gives) or over all headings (a scan
// without a dominant wall), on 1 or 2 threads (the second argument).
#include <benchmark/benchmark.h>

#include <random>
#include <string>

#include "localizer/filter/plan_search.hpp"
#include "test/synthetic_room.hpp"

namespace cl = conicloc::localizer;
namespace ct = conicloc::test;

namespace {

conicloc::maps::PlaneMap room_grid(int n) {
  conicloc::maps::PlaneMap map;
  map.storeys.push_back({"ground", 0.0, 3.0});
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> px(1.0, 8.0), py(1.0, 4.4);
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      const double x0 = 10.0 * a, y0 = 6.0 * b;
      conicloc::maps::Cell cell;
      cell.id = "room" + std::to_string(a) + "_" + std::to_string(b);
      cell.storey = 0;
      cell.footprint = {{x0, y0}, {x0 + 10, y0}, {x0 + 10, y0 + 6}, {x0, y0 + 6}};
      cell.bounds =
          Eigen::AlignedBox3d(Eigen::Vector3d(x0, y0, 0), Eigen::Vector3d(x0 + 10, y0 + 6, 3));
      cell.ceiling_z = 3.0;
      cell.representative_point = {x0 + 5, y0 + 3, 0};
      const int index = static_cast<int>(map.cells.size());
      map.cells.push_back(cell);
      ct::add_box(map, index, {x0, y0, 0}, {x0 + 10, y0 + 6, 3}, true);
      // The first room's pillar where the box room has it: the sensor stands clear of it.
      const bool first = a == 0 && b == 0;
      const double x = first ? 7.0 : x0 + px(rng), y = first ? 1.0 : y0 + py(rng);
      ct::add_box(map, index, {x, y, 0}, {x + 1.0, y + 0.6, 3.0}, false);
    }
  }
  return map;
}

conicloc::sensor::Scan first_room_scan(const conicloc::maps::PlaneMap& map) {
  std::mt19937_64 rng(1);
  ct::SyntheticScanOptions options;
  options.azimuth_step_rad = 0.2 * M_PI / 180.0;
  options.range_sigma_m = 0.03;
  return ct::make_scan(map, cl::make_pose(3.0, 2.5, 1.2, 0.4), options, rng);
}

void BM_BuildPlanFields(benchmark::State& state) {
  const auto map = room_grid(static_cast<int>(state.range(0)));
  const cl::FreeSpace free_space(map);
  std::size_t bytes = 0;
  for (auto _ : state) {
    const cl::PlanSearch search(map, free_space, 1.2, {});
    bytes = search.memory_bytes();
    benchmark::DoNotOptimize(bytes);
  }
  state.counters["floor_m2"] = 60.0 * static_cast<double>(state.range(0) * state.range(0));
  state.counters["MiB"] = static_cast<double>(bytes) / (1024.0 * 1024.0);
}

void BM_PlanSearch(benchmark::State& state, bool proposed_headings) {
  const auto map = room_grid(static_cast<int>(state.range(0)));
  const cl::FreeSpace free_space(map);
  const cl::PlanSearch search(map, free_space, 1.2, {});
  const auto scan = first_room_scan(map);
  // The box room's walls run along x and y: ψ and ψ + π for each, about the true 0.4 rad.
  const std::vector<double> headings =
      proposed_headings ? std::vector<double>{0.4, 0.4 + M_PI / 2, 0.4 - M_PI / 2, 0.4 - M_PI}
                        : std::vector<double>{};
  std::size_t found = 0;
  for (auto _ : state) {
    const auto candidates = search.search(scan, headings, static_cast<int>(state.range(1)));
    found = candidates.size();
    benchmark::DoNotOptimize(found);
  }
  state.counters["floor_m2"] = 60.0 * static_cast<double>(state.range(0) * state.range(0));
  state.counters["candidates"] = static_cast<double>(found);
}

}  // namespace

BENCHMARK(BM_BuildPlanFields)->Arg(1)->Arg(4)->Arg(16)->Arg(32)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PlanSearch, proposed_headings, true)
    ->ArgsProduct({{1, 4, 16, 32}, {1, 2}})
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PlanSearch, all_headings, false)
    ->ArgsProduct({{1, 4, 16, 32}, {1, 2}})
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
