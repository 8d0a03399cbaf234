// `conicloc generate-building --kind KIND --seed N --out FILE.gml`: an IndoorGML building drawn
// from a seed (sim/building_generator), to evaluate on buildings the localizer was not tuned on;
// `--storeys S --plate-tiles P` size a storeys building for cost-against-size measurements.
#include <spdlog/spdlog.h>

#include <cstdint>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>

#include "io/indoorgml.hpp"
#include "sim/building_generator.hpp"
#include "tools/commands.hpp"

namespace conicloc::tools {
namespace {

struct GenerateBuildingOptions {
  std::string kind;
  std::uint64_t seed = 1;
  sim::BuildingScale scale;
  std::string out_path;
};

void run_generate_building(const GenerateBuildingOptions& options) {
  const std::string text = sim::generate_building_gml(options.kind, options.seed, options.scale);
  {
    std::ofstream out(options.out_path, std::ios::binary);
    out << text;
    if (!out) throw std::runtime_error("cannot write " + options.out_path);
  }
  // Read back what was written, so the log says what the localizer will see.
  const auto loaded = io::load_indoorgml(options.out_path);
  spdlog::info("wrote {}: generated {} building, seed {}, {} bytes", options.out_path, options.kind,
               options.seed, text.size());
  spdlog::info("{} cells, {} doors, {} storeys, {} planes, {} navigation edges",
               loaded.map.cells.size(), loaded.report.doors, loaded.map.storeys.size(),
               loaded.map.polygons.size(), loaded.map.navigation.edges.size());
}

}  // namespace

void add_generate_building_command(CLI::App& app) {
  auto options = std::make_shared<GenerateBuildingOptions>();
  auto* cmd =
      app.add_subcommand("generate-building", "Write an IndoorGML building generated from a seed");
  cmd->add_option("--kind", options->kind, "Kind of building")
      ->required()
      ->check(CLI::IsMember(sim::generated_building_kinds()));
  cmd->add_option("--seed", options->seed, "Seed of every dimension and position")
      ->capture_default_str();
  cmd->add_option("--storeys", options->scale.storeys,
                  "Storeys of a storeys building (default: drawn from the seed, 2-4)")
      ->check(CLI::Range(1, sim::kMaxStoreys));
  cmd->add_option("--plate-tiles", options->scale.plate_tiles,
                  "Floor plates along the corridor of a storeys building (floor area about x this)")
      ->capture_default_str()
      ->check(CLI::Range(1, sim::kMaxPlateTiles));
  cmd->add_option("--out", options->out_path, "IndoorGML file to write")->required();
  cmd->callback([options] { run_generate_building(*options); });
}

}  // namespace conicloc::tools
