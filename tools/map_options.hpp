#pragma once
// The options that change how a building model is read (--unit-scale, --storey-height,
// --close-doors), added the same way to every command that loads a map, and the loading itself.

#include <CLI/CLI.hpp>

#include "io/indoorgml.hpp"
#include "maps/unit_plausibility.hpp"

namespace conicloc::tools {

/// Adds --storey-height, --unit-scale and --close-doors to `command`, filling `options`.
void add_map_load_options(CLI::App* command, io::MapLoadOptions& options);

/// The model at `path` read with `options`; its load warnings logged, naming the file.
io::LoadedMap load_map(const std::string& path, const io::MapLoadOptions& options);

/// Whether the loaded model's sizes are those of a building in metres (see maps::check_units).
maps::UnitCheck check_map_units(const io::LoadedMap& loaded, const io::MapLoadOptions& options);

/// Throws io::InputError naming `path`, what is implausible and the --unit-scale to use, unless
/// the sizes are plausible.
void require_plausible_units(const std::string& path, const io::LoadedMap& loaded,
                             const io::MapLoadOptions& options);

}  // namespace conicloc::tools
