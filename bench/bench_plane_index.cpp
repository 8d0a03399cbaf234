// PlaneIndex queries against brute force (closest point of every polygon) on a synthetic
// building: a grid of 5 m x 5 m x 3 m rooms (floor, ceiling, four walls each), one or more
// storeys. Ranges 5, 15 and 50 m; compare the index and brute-force rows of the same range.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <random>

#include "maps/plane_index.hpp"

namespace cm = conicloc::maps;

namespace {

void add_polygon(cm::PlaneMap& map, const cm::Ring3& ring) {
  cm::PlanarPolygon polygon;
  if (cm::make_planar_polygon(ring, {}, polygon)) map.polygons.push_back(std::move(polygon));
}

// rooms_x x rooms_y rooms per storey; 6 polygons per room.
cm::PlaneMap grid_building(int rooms_x, int rooms_y, int storeys) {
  cm::PlaneMap map;
  const double room = 5.0;
  const double height = 3.0;
  for (int s = 0; s < storeys; ++s) {
    const double z0 = s * (height + 0.2);
    const double z1 = z0 + height;
    for (int i = 0; i < rooms_x; ++i) {
      for (int j = 0; j < rooms_y; ++j) {
        const double x0 = i * room, x1 = x0 + room, y0 = j * room, y1 = y0 + room;
        add_polygon(map, {{x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0}});
        add_polygon(map, {{x0, y0, z1}, {x0, y1, z1}, {x1, y1, z1}, {x1, y0, z1}});
        add_polygon(map, {{x0, y0, z0}, {x0, y0, z1}, {x1, y0, z1}, {x1, y0, z0}});
        add_polygon(map, {{x1, y0, z0}, {x1, y0, z1}, {x1, y1, z1}, {x1, y1, z0}});
        add_polygon(map, {{x1, y1, z0}, {x1, y1, z1}, {x0, y1, z1}, {x0, y1, z0}});
        add_polygon(map, {{x0, y1, z0}, {x0, y1, z1}, {x0, y0, z1}, {x0, y0, z0}});
      }
    }
  }
  return map;
}

// Second argument of every query benchmark: 0 = 480 polygons (50 m x 40 m, one storey),
// 1 = 9600 polygons (200 m x 100 m, two storeys).
const cm::PlaneMap& building(std::int64_t size = 0) {
  static const cm::PlaneMap small = grid_building(10, 8, 1);
  static const cm::PlaneMap large = grid_building(40, 20, 2);
  return size == 0 ? small : large;
}

std::vector<Eigen::Vector3d> query_points(std::int64_t size = 0) {
  std::mt19937 rng(1);
  const double extent = size == 0 ? 1.0 : 4.0;
  std::uniform_real_distribution<double> x(0.0, 50.0 * extent), y(0.0, 40.0 * extent), z(0.5, 2.5);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 256; ++i) points.emplace_back(x(rng), y(rng), z(rng));
  return points;
}

void BM_IndexWithinPoint(benchmark::State& state) {
  const cm::PlaneIndex index(building(state.range(1)));
  const auto points = query_points(state.range(1));
  const double range_m = static_cast<double>(state.range(0));
  std::size_t i = 0, found = 0;
  for (auto _ : state) {
    const auto result = index.within(points[i++ % points.size()], range_m);
    found += result.size();
    benchmark::DoNotOptimize(result.data());
  }
  state.counters["polygons"] = static_cast<double>(building(state.range(1)).polygons.size());
  state.counters["found"] = static_cast<double>(found) / static_cast<double>(state.iterations());
}

void BM_BruteForceWithinPoint(benchmark::State& state) {
  const auto& map = building(state.range(1));
  const auto points = query_points(state.range(1));
  const double range_m = static_cast<double>(state.range(0));
  std::size_t i = 0, found = 0;
  for (auto _ : state) {
    const Eigen::Vector3d& p = points[i++ % points.size()];
    std::vector<int> result;
    for (std::size_t k = 0; k < map.polygons.size(); ++k) {
      if ((cm::closest_point(map.polygons[k], p) - p).norm() <= range_m) {
        result.push_back(static_cast<int>(k));
      }
    }
    found += result.size();
    benchmark::DoNotOptimize(result.data());
  }
  state.counters["found"] = static_cast<double>(found) / static_cast<double>(state.iterations());
}

// A particle cloud's bounding box: 2 m x 2 m x 0.2 m around each query point.
void BM_IndexWithinBox(benchmark::State& state) {
  const cm::PlaneIndex index(building(state.range(1)));
  const auto points = query_points(state.range(1));
  const double range_m = static_cast<double>(state.range(0));
  const Eigen::Vector3d half(1.0, 1.0, 0.1);
  std::size_t i = 0;
  for (auto _ : state) {
    const Eigen::Vector3d& p = points[i++ % points.size()];
    const auto result = index.within(Eigen::AlignedBox3d(p - half, p + half), range_m);
    benchmark::DoNotOptimize(result.data());
  }
}

void BM_BruteForceWithinBox(benchmark::State& state) {
  const auto& map = building(state.range(1));
  const auto points = query_points(state.range(1));
  const double range_m = static_cast<double>(state.range(0));
  const Eigen::Vector3d half(1.0, 1.0, 0.1);
  std::size_t i = 0;
  for (auto _ : state) {
    const Eigen::Vector3d& p = points[i++ % points.size()];
    const Eigen::AlignedBox3d box(p - half, p + half);
    std::vector<int> result;
    for (std::size_t k = 0; k < map.polygons.size(); ++k) {
      if (cm::distance_to_box(map.polygons[k], box) <= range_m) {
        result.push_back(static_cast<int>(k));
      }
    }
    benchmark::DoNotOptimize(result.data());
  }
}

void BM_IndexBuild(benchmark::State& state) {
  const auto map = grid_building(static_cast<int>(state.range(0)), 8, 2);
  for (auto _ : state) {
    const cm::PlaneIndex index(map);
    benchmark::DoNotOptimize(&index);
  }
  state.counters["polygons"] = static_cast<double>(map.polygons.size());
}

}  // namespace

BENCHMARK(BM_IndexWithinPoint)->ArgsProduct({{5, 15, 50}, {0, 1}});
BENCHMARK(BM_BruteForceWithinPoint)->ArgsProduct({{5, 15, 50}, {0, 1}});
BENCHMARK(BM_IndexWithinBox)->ArgsProduct({{5, 15, 50}, {0, 1}});
BENCHMARK(BM_BruteForceWithinBox)->ArgsProduct({{5, 15, 50}, {0, 1}});
BENCHMARK(BM_IndexBuild)->Arg(10)->Arg(40);

BENCHMARK_MAIN();
