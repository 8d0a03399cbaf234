#pragma once
// Buildings generated from a seed (issue 14), to judge the localizer on buildings it was never
// tuned on: long corridors with door openings, mirror-image wings, an open hall with pillars,
// identical storeys stacked with stairs, with sloped ceilings and non-Manhattan walls among them.
// Each is written as IndoorGML 1.0.3 text that io::load_indoorgml reads like any other file.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace conicloc::sim {

/// The kinds of generated building, in a fixed order: "corridor", "wings", "hall", "storeys".
std::vector<std::string> generated_building_kinds();

/// The size of a "storeys" building, for measuring cost against building size (issue 15): the
/// storey count (0: drawn from the seed, 2–4) and how many floor plates follow each other along
/// its corridor (1: the seed's building). A scaled building keeps room for two stairwell lanes
/// north of the first plate's corridor whatever its storey count, so its floor area grows about
/// in proportion to the plates (P plates: a little more than P times one plate's).
struct BuildingScale {
  int storeys = 0;
  int plate_tiles = 1;

  bool is_default() const { return storeys == 0 && plate_tiles == 1; }
};

/// "SxP" (storeys x plates), as the scale is written in a spec and in names.
std::string scale_text(const BuildingScale& scale);

/// An IndoorGML 1.0.3 document (text) of a building of `kind` drawn from `seed`: same (kind, seed,
/// scale), same bytes. Throws std::invalid_argument naming the known kinds for an unknown kind,
/// and for a scale other than the default on a kind other than "storeys" or out of its range
/// (1–kMaxStoreys storeys, 1–kMaxPlateTiles plates).
std::string generate_building_gml(const std::string& kind, std::uint64_t seed,
                                  const BuildingScale& scale = {});

constexpr int kMaxStoreys = 50;
constexpr int kMaxPlateTiles = 16;

/// Parses "generated:KIND:SEED" (e.g. "generated:corridor:3") and "generated:storeys:SEED:SxP"
/// (S storeys, 0 for the seed's count; P floor plates; e.g. "generated:storeys:1:10x4"); nullopt
/// when `spec` does not start with "generated:"; throws std::invalid_argument for a malformed one.
struct GeneratedBuildingSpec {
  std::string kind;
  std::uint64_t seed = 0;
  BuildingScale scale;
};
std::optional<GeneratedBuildingSpec> parse_generated_building_spec(const std::string& spec);

}  // namespace conicloc::sim
