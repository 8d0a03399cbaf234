#include "tools/map_options.hpp"

#include <spdlog/spdlog.h>

#include <sstream>

#include "io/input_error.hpp"

namespace conicloc::tools {

void add_map_load_options(CLI::App* command, io::MapLoadOptions& options) {
  command
      ->add_option("--storey-height", options.storey_height_m,
                   "Wall height for 2D-only models, metres")
      ->check(CLI::PositiveNumber);
  command
      ->add_option("--unit-scale", options.unit_scale,
                   "File units to metres, e.g. 0.001 for millimetres")
      ->check(CLI::PositiveNumber);
  command->add_flag("--close-doors", options.close_doors,
                    "Keep doors between navigable cells as walls");
}

io::LoadedMap load_map(const std::string& path, const io::MapLoadOptions& options) {
  auto loaded = io::load_indoorgml(path, options);
  for (const auto& warning : loaded.report.warnings) spdlog::warn("{}: {}", path, warning);
  return loaded;
}

maps::UnitCheck check_map_units(const io::LoadedMap& loaded, const io::MapLoadOptions& options) {
  return maps::check_units(loaded.map, options.unit_scale, !loaded.report.extruded_2d);
}

void require_plausible_units(const std::string& path, const io::LoadedMap& loaded,
                             const io::MapLoadOptions& options) {
  const maps::UnitCheck units = check_map_units(loaded, options);
  if (units.plausible) return;
  std::ostringstream what;
  what << "implausible sizes for a building: " << units.problem << "; ";
  if (units.suggested_unit_scale) {
    what << "the model is probably in other units: give --unit-scale "
         << *units.suggested_unit_scale << " (file units to metres)";
  } else {
    what << "check --unit-scale (file units to metres)";
  }
  what << ", or --trust-units to localize in it as it is";
  throw io::InputError(path, "", what.str());
}

}  // namespace conicloc::tools
