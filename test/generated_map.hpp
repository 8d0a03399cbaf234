#pragma once
// A building drawn by the project's generator (sim/building_generator.hpp), loaded as a map the
// way a user's IndoorGML file is: written out and read back.

#include <filesystem>
#include <fstream>
#include <string>

#include "io/indoorgml.hpp"
#include "sim/building_generator.hpp"
#include "test/temp_path.hpp"

namespace conicloc::test {

inline maps::PlaneMap generated_map(const std::string& kind, std::uint64_t seed,
                                    const sim::BuildingScale& scale = {}) {
  const auto path = unique_temp_path(kind + ".gml");
  std::ofstream(path) << sim::generate_building_gml(kind, seed, scale);
  auto map = io::load_indoorgml(path.string()).map;
  std::filesystem::remove(path);
  return map;
}

}  // namespace conicloc::test
