// The conic sensor model's per-particle cost: one full predicted scan (16 rings, a culled view of
// a real building: the shared FJK-Haus IndoorGML model, else a synthetic grid of rooms) and the
// evaluation of the predicted scan lines at sorted measured azimuths (per beam).
//   ./bench_conic            targets: predict < 20 µs per pose, evaluate < 2 ns per beam
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <numeric>
#include <random>

#include "io/indoorgml.hpp"
#include "localizer/conic/conic_scan_predictor.hpp"
#include "localizer/conic/plane_culling.hpp"
#include "maps/plane_index.hpp"
#include "sensor/builtin_calibration.hpp"
#include "sim/building_generator.hpp"

namespace cl = conicloc::localizer;
namespace cm = conicloc::maps;

namespace {

cm::PlaneMap synthetic_building() {
  cm::PlaneMap map;
  auto add = [&](const cm::Ring3& ring) {
    cm::PlanarPolygon polygon;
    if (cm::make_planar_polygon(ring, {}, polygon)) map.polygons.push_back(std::move(polygon));
  };
  for (int i = 0; i < 8; ++i) {
    for (int j = 0; j < 6; ++j) {
      const double x0 = 5.0 * i, x1 = x0 + 5.0, y0 = 5.0 * j, y1 = y0 + 5.0;
      add({{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}});
      add({{x0, y0, 3}, {x0, y1, 3}, {x1, y1, 3}, {x1, y0, 3}});
      add({{x0, y0, 0}, {x0, y0, 3}, {x1, y0, 3}, {x1, y0, 0}});
      add({{x1, y0, 0}, {x1, y0, 3}, {x1, y1, 3}, {x1, y1, 0}});
      add({{x1, y1, 0}, {x1, y1, 3}, {x0, y1, 3}, {x0, y1, 0}});
      add({{x0, y1, 0}, {x0, y1, 3}, {x0, y0, 3}, {x0, y0, 0}});
    }
  }
  return map;
}

struct Scene {
  cm::PlaneMap map;
  std::string name;
  std::vector<cl::Pose3> poses;
};

const Scene& scene() {
  static const Scene s = [] {
    Scene out;
    const std::string fjk = std::string(CONICLOC_SHARED_DATA) +
                            "/indoorgml/FJK-Haus_IndoorGML_withEXR-corrected_1_0_3.gml";
    if (std::filesystem::exists(fjk)) {
      out.map = conicloc::io::load_indoorgml(fjk).map;
      out.name = "FJK-Haus";
    } else {
      out.map = synthetic_building();
      out.name = "synthetic 8x6 rooms";
    }
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> yaw(0.0, 2 * std::numbers::pi);
    for (const cm::Cell& cell : out.map.cells) {
      if (!cell.navigable) continue;
      const Eigen::Vector3d p = cell.representative_point;
      out.poses.push_back(cl::make_pose(p.x(), p.y(), p.z() + 1.2, yaw(rng)));
    }
    if (out.poses.empty()) {
      for (int i = 0; i < 48; ++i) {
        out.poses.push_back(cl::make_pose(2.5 + 5.0 * (i % 8), 2.5 + 5.0 * (i / 8), 1.2, yaw(rng)));
      }
    }
    return out;
  }();
  return s;
}

void predict_culled_scan(benchmark::State& state, const cl::PredictorConfig& config) {
  const Scene& s = scene();
  const auto calibration =
      conicloc::sensor::builtin_calibration(conicloc::sensor::SensorModel::VLP16);
  const cm::PlaneIndex index(s.map);
  const cl::PlaneCuller culler(s.map, index, calibration, {}, 30.0);
  const cl::ConicScanPredictor predictor(s.map, calibration, config);
  std::vector<std::vector<int>> culled;
  double kept = 0.0;
  for (const auto& pose : s.poses) {
    culled.push_back(culler.cull(pose).kept);
    kept += static_cast<double>(culled.back().size());
  }
  cl::PredictedScan predicted;
  std::size_t i = 0, pieces = 0;
  for (auto _ : state) {
    predictor.predict(s.poses[i], culled[i], predicted);
    pieces += predicted.rings[0].piece_count();
    benchmark::DoNotOptimize(predicted.rings.data());
    i = (i + 1) % s.poses.size();
  }
  state.SetLabel(s.name);
  state.counters["polygons_in_map"] = static_cast<double>(s.map.polygons.size());
  state.counters["culled_view_polygons"] = kept / static_cast<double>(s.poses.size());
  state.counters["poses"] = static_cast<double>(s.poses.size());
}
void BM_PredictCulledScan(benchmark::State& state) {
  predict_culled_scan(state, {});
}
BENCHMARK(BM_PredictCulledScan)->Unit(benchmark::kMicrosecond);

// Baseline of the same run: without the per-ring elevation rejection of polygons.
void BM_PredictCulledScanNoElevationRejection(benchmark::State& state) {
  predict_culled_scan(state, {.reject_by_elevation = false});
}
BENCHMARK(BM_PredictCulledScanNoElevationRejection)->Unit(benchmark::kMicrosecond);

// Baseline of the same run: one inside test per interval instead of crossing parity.
void BM_PredictCulledScanMidpointTests(benchmark::State& state) {
  predict_culled_scan(state, {.classify_by_crossing_parity = false});
}
BENCHMARK(BM_PredictCulledScanMidpointTests)->Unit(benchmark::kMicrosecond);

// Baseline of the same run: every polygon clipped, none skipped as hidden behind nearer arcs.
void BM_PredictCulledScanNoOcclusionSkip(benchmark::State& state) {
  predict_culled_scan(state, {.skip_occluded = false});
}
BENCHMARK(BM_PredictCulledScanNoOcclusionSkip)->Unit(benchmark::kMicrosecond);

// A generated storeys building of range(0) storeys and range(1) floor plates, every polygon a
// candidate (as for a searching cloud, whose box holds the building), predicted at each
// corridor's centre line; range(2) = 1 skips hidden polygons, 0 is the baseline without.
// A generated storeys building of `storeys` × `plates` and poses along its corridors' centre lines.
struct ScaledScene {
  cm::PlaneMap map;
  std::vector<cl::Pose3> poses;
};

ScaledScene scaled_scene(int storeys, int plates) {
  const conicloc::sim::BuildingScale scale{storeys, plates};
  const auto path = std::filesystem::temp_directory_path() /
                    ("bench_conic_storeys_" + conicloc::sim::scale_text(scale) + ".gml");
  std::ofstream(path) << conicloc::sim::generate_building_gml("storeys", 1, scale);
  ScaledScene scene{conicloc::io::load_indoorgml(path.string()).map, {}};
  std::filesystem::remove(path);
  for (const cm::Cell& cell : scene.map.cells) {
    if (cell.id.find("Corridor") == std::string::npos) continue;
    const Eigen::Vector3d c = cell.bounds.center();
    for (int i = 0; i < 8; ++i) {
      const double x = cell.bounds.min().x() + (i + 0.5) / 8.0 * cell.bounds.sizes().x();
      scene.poses.push_back(cl::make_pose(x, c.y(), cell.floor_z + 0.8, 0.7 * i));
    }
  }
  return scene;
}

// One prediction of `rings` (every ring when empty), every polygon a candidate.
void predict_in_scaled_building(benchmark::State& state, const ScaledScene& scene,
                                const cl::PredictorConfig& config, const std::vector<int>& rings) {
  const auto calibration =
      conicloc::sensor::builtin_calibration(conicloc::sensor::SensorModel::VLP16);
  const cl::ConicScanPredictor predictor(scene.map, calibration, config);
  std::vector<int> all(scene.map.polygons.size());
  std::iota(all.begin(), all.end(), 0);
  cl::PredictedScan predicted;
  std::size_t i = 0;
  double occluded = 0.0, clipped = 0.0;
  for (auto _ : state) {
    if (rings.empty()) {
      predictor.predict(scene.poses[i], predicted);
    } else {
      predictor.predict(scene.poses[i], all, rings, predicted);
    }
    occluded += static_cast<double>(predicted.ring_polygons_occluded);
    clipped += static_cast<double>(predicted.ring_polygons_clipped);
    benchmark::DoNotOptimize(predicted.rings.data());
    i = (i + 1) % scene.poses.size();
  }
  state.counters["polygons"] = static_cast<double>(scene.map.polygons.size());
  state.counters["occluded_pairs"] = occluded / static_cast<double>(state.iterations());
  state.counters["clipped_pairs"] = clipped / static_cast<double>(state.iterations());
}

void BM_PredictInScaledBuilding(benchmark::State& state) {
  const ScaledScene scene =
      scaled_scene(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  predict_in_scaled_building(state, scene, {.skip_occluded = state.range(2) == 1}, {});
}
BENCHMARK(BM_PredictInScaledBuilding)
    ->ArgsProduct({{1, 10}, {1, 4}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);

// The 4 rings a searching cloud scores (localizer/filter/search_rings.hpp: 2, 6, 10, 14).
void BM_PredictFourRingsInScaledBuilding(benchmark::State& state) {
  const ScaledScene scene =
      scaled_scene(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  predict_in_scaled_building(state, scene, {}, {2, 6, 10, 14});
}
BENCHMARK(BM_PredictFourRingsInScaledBuilding)
    ->ArgsProduct({{1, 10}, {1, 4}})
    ->Unit(benchmark::kMicrosecond);

void BM_CullPerPose(benchmark::State& state) {
  const Scene& s = scene();
  const auto calibration =
      conicloc::sensor::builtin_calibration(conicloc::sensor::SensorModel::VLP16);
  const cm::PlaneIndex index(s.map);
  const cl::PlaneCuller culler(s.map, index, calibration, {}, 30.0);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(culler.cull(s.poses[i]).kept.size());
    i = (i + 1) % s.poses.size();
  }
  state.SetLabel(s.name);
}
BENCHMARK(BM_CullPerPose)->Unit(benchmark::kMicrosecond);

// Evaluates all 16 rings at 1800 sorted azimuths each (0.2°, the VLP-16 at 10 Hz): per beam.
void BM_EvaluatePerBeam(benchmark::State& state) {
  const Scene& s = scene();
  const auto calibration =
      conicloc::sensor::builtin_calibration(conicloc::sensor::SensorModel::VLP16);
  const cl::ConicScanPredictor predictor(s.map, calibration);
  cl::PredictedScan predicted;
  predictor.predict(s.poses[0], predicted);
  std::vector<double> azimuths;
  const int beams = static_cast<int>(state.range(0));
  for (int i = 0; i < beams; ++i) azimuths.push_back(i * 2 * std::numbers::pi / beams);
  cl::AzimuthSamples samples;
  samples.assign(azimuths);
  std::vector<double> ranges(azimuths.size());
  for (auto _ : state) {
    for (const auto& ring : predicted.rings) {
      ring.evaluate_sorted(samples, ranges);
      benchmark::DoNotOptimize(ranges.data());
    }
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(predicted.rings.size()) *
                          beams);
  state.SetLabel(s.name);
}
BENCHMARK(BM_EvaluatePerBeam)->Arg(1800)->Arg(125);

}  // namespace

BENCHMARK_MAIN();
