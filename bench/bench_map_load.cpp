// IndoorGML load time (parse + PlaneMap build) on the shared real models and the example
// building. Counters: bytes/s and polygons/s; per-MB and per-polygon times follow from them.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "io/indoorgml.hpp"
#include "io/indoorgml_structure.hpp"
#include "io/xml_source.hpp"

namespace {

void load_file(benchmark::State& state, const std::string& path) {
  if (!std::filesystem::exists(path)) {
    state.SkipWithError(("absent: " + path).c_str());
    return;
  }
  int polygons = 0;
  std::size_t bytes = 0;
  for (auto _ : state) {
    const auto loaded = conicloc::io::load_indoorgml(path);
    polygons = loaded.report.polygons_read;
    bytes = loaded.report.file_bytes;
    benchmark::DoNotOptimize(loaded.map.polygons.data());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * bytes));
  state.counters["polygons"] = polygons;
  state.counters["polygons_per_s"] = benchmark::Counter(
      static_cast<double>(polygons), benchmark::Counter::kIsIterationInvariantRate);
}

// Parse only (XML + structure walk), to split the time between io/ and maps/.
void parse_file(benchmark::State& state, const std::string& path) {
  if (!std::filesystem::exists(path)) {
    state.SkipWithError(("absent: " + path).c_str());
    return;
  }
  std::size_t bytes = 0;
  for (auto _ : state) {
    const conicloc::io::XmlSource source(path);
    const auto raw = conicloc::io::read_indoorgml_structure(source);
    bytes = source.size_bytes();
    benchmark::DoNotOptimize(raw.cells.data());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * bytes));
}

const std::string kShared = std::string(CONICLOC_SHARED_DATA) + "/indoorgml/";

}  // namespace

BENCHMARK_CAPTURE(load_file, fjk, kShared + "FJK-Haus_IndoorGML_withEXR-corrected_1_0_3.gml")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(load_file, ku,
                  kShared + "KU-Central-Plaza-IndoorGML-PS-without-Texture-04-26-corrected.gml")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(load_file, pnu_2d, kShared + "PNU-bldg313-4F-2D-190612.gml")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(load_file, put_outer, kShared + "put-outer_examples_03_model.gml")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(load_file, example, std::string(CONICLOC_EXAMPLE_MAP))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(parse_file, fjk, kShared + "FJK-Haus_IndoorGML_withEXR-corrected_1_0_3.gml")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(parse_file, ku,
                  kShared + "KU-Central-Plaza-IndoorGML-PS-without-Texture-04-26-corrected.gml")
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
