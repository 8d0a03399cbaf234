#pragma once
// The buildings of an evaluation sweep: IndoorGML files, and buildings drawn by the generator,
// `generated:KIND:SEED` (one building), `generated:storeys:SEED:SxP` (one building of S storeys
// and P floor plates) or `generated:KIND` (a new building for every sweep seed, drawn with that
// seed, so no setting can be fitted to one building). A generated building is
// written as IndoorGML into the report folder and read back like any file, so the reader is
// exercised too.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/indoorgml.hpp"
#include "maps/plane_map.hpp"
#include "sim/building_generator.hpp"

namespace conicloc::run {

struct Building {
  std::string name;   ///< unique within the sweep: the file stem, or KIND-sSEED
  std::string group;  ///< its robustness table row: the name, or KIND-s* when drawn per seed
  maps::PlaneMap map;
  double floor_area_m2 = 0.0;  ///< navigable floor, plan view (localizer::FreeSpace)
  bool two_sided_walls = false;
  std::vector<std::string> warnings;  ///< the IndoorGML reader's, each as "<file>: <warning>"
};

/// One entry of the sweep's building list, not loaded yet.
struct BuildingSource {
  std::string map;                    ///< the path or `generated:…` as given
  std::string name;                   ///< as Building::name; for a per-seed kind, the KIND
  std::string kind;                   ///< the generator's kind; empty for a file
  std::optional<std::uint64_t> seed;  ///< a fixed generated building's seed
  sim::BuildingScale scale;           ///< a generated storeys building's size
  io::MapLoadOptions load;            ///< how a file is read (generated ones: the defaults)

  bool per_seed() const { return !kind.empty() && !seed; }
};

/// Checks every entry before any work: files exist, generated kinds are known (throws
/// io::InputError naming the entry otherwise); file stems made unique with -2, -3, ….
std::vector<BuildingSource> building_sources(const std::vector<std::string>& maps);

/// Loads `source`, for sweep seed `sweep_seed` when it is drawn per seed; a generated building's
/// IndoorGML goes to `buildings_dir`/KIND-SEED.gml first. Throws what the generator or the
/// IndoorGML reader throws; the reader's warnings are kept in Building::warnings.
Building load_building(const BuildingSource& source, std::uint64_t sweep_seed,
                       const std::filesystem::path& buildings_dir);

}  // namespace conicloc::run
