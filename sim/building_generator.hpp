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

/// An IndoorGML 1.0.3 document (text) of a building of `kind` drawn from `seed`: same (kind, seed),
/// same bytes. Throws std::invalid_argument naming the known kinds for an unknown kind.
std::string generate_building_gml(const std::string& kind, std::uint64_t seed);

/// Parses "generated:KIND:SEED" (e.g. "generated:corridor:3"); nullopt when `spec` does not start
/// with "generated:"; throws std::invalid_argument for a malformed one.
struct GeneratedBuildingSpec {
  std::string kind;
  std::uint64_t seed = 0;
};
std::optional<GeneratedBuildingSpec> parse_generated_building_spec(const std::string& spec);

}  // namespace conicloc::sim
