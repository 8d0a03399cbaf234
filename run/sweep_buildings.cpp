#include "run/sweep_buildings.hpp"

#include <algorithm>
#include <fstream>

#include "eval/sweep_plan.hpp"
#include "eval/sweep_spec.hpp"
#include "io/indoorgml.hpp"
#include "io/input_error.hpp"
#include "localizer/filter/free_space.hpp"
#include "sim/building_generator.hpp"

namespace conicloc::run {
namespace {

namespace fs = std::filesystem;

BuildingSource generated_source(const std::string& map) {
  BuildingSource source;
  source.map = map;
  const std::string rest = map.substr(std::string("generated:").size());
  if (rest.find(':') == std::string::npos) {
    source.kind = rest;
  } else {
    std::optional<sim::GeneratedBuildingSpec> spec;
    try {
      spec = sim::parse_generated_building_spec(map);
    } catch (const std::exception& e) {
      throw io::InputError(map, "", e.what());
    }
    if (!spec) throw io::InputError(map, "", "expected generated:KIND or generated:KIND:SEED");
    source.kind = spec->kind;
    source.seed = spec->seed;
    source.scale = spec->scale;
  }
  const auto kinds = sim::generated_building_kinds();
  if (std::find(kinds.begin(), kinds.end(), source.kind) == kinds.end()) {
    std::string known;
    for (const auto& kind : kinds) known += (known.empty() ? "" : ", ") + kind;
    throw io::InputError(map, "",
                         "unknown generated building '" + source.kind + "' (known: " + known + ")");
  }
  source.name = source.seed ? source.kind + "-s" + std::to_string(*source.seed) : source.kind;
  if (!source.scale.is_default()) source.name.append("-").append(sim::scale_text(source.scale));
  return source;
}

}  // namespace

std::vector<BuildingSource> building_sources(const std::vector<std::string>& maps) {
  std::vector<BuildingSource> sources;
  for (const auto& map : maps) {
    if (eval::is_generated_map(map)) {
      sources.push_back(generated_source(map));
      continue;
    }
    if (!fs::is_regular_file(map)) throw io::InputError(map, "", "no such building file");
    BuildingSource source;
    source.map = map;
    const std::string stem = fs::path(map).stem().string();
    source.name = stem;
    for (int k = 2; std::any_of(sources.begin(), sources.end(),
                                [&](const BuildingSource& s) { return s.name == source.name; });
         ++k) {
      source.name = stem + "-" + std::to_string(k);
    }
    sources.push_back(std::move(source));
  }
  return sources;
}

Building load_building(const BuildingSource& source, std::uint64_t sweep_seed,
                       const fs::path& buildings_dir) {
  Building building;
  building.name = source.name;
  building.group = source.name;
  std::string path = source.map;
  if (!source.kind.empty()) {
    const std::uint64_t seed = source.seed.value_or(sweep_seed);
    if (source.per_seed()) {
      building.name = eval::building_name({source.kind, true}, seed);
      building.group = source.kind + "-s*";
    }
    fs::create_directories(buildings_dir);
    std::string stem = source.kind + "-" + std::to_string(seed);
    if (!source.scale.is_default()) stem.append("-").append(sim::scale_text(source.scale));
    path = (buildings_dir / (stem + ".gml")).string();
    std::ofstream out(path);
    out << sim::generate_building_gml(source.kind, seed, source.scale);
    out.flush();
    if (!out) throw io::InputError(path, "", "cannot write the generated building");
  }
  auto loaded = io::load_indoorgml(path, source.load);
  for (const auto& warning : loaded.report.warnings)
    building.warnings.push_back(path + ": " + warning);
  building.two_sided_walls = loaded.report.two_sided_faces > 0;
  building.map = std::move(loaded.map);
  building.floor_area_m2 = localizer::FreeSpace(building.map).total_area_m2();
  return building;
}

}  // namespace conicloc::run
