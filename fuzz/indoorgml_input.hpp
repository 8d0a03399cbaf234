#pragma once
// Fuzz driver: io::load_indoorgml() on arbitrary bytes (XML parsing, IndoorGML structure, GML
// geometry, xlinks, and the PlaneMap build: triangulation, plane merging, door cutting). Shared
// by fuzz/fuzz_indoorgml.cpp and test/test_fuzz_regressions.cpp.
//
// Seeds are valid IndoorGML 1.0.x / 2.0 documents (test/data/indoorgml, the example building), so
// most inputs are a valid document mutated; fuzz/gml.dict gives the mutator the element names.
// io::InputError is the documented rejection of a bad model; any other exception is a finding.
// Odd-sized inputs load with close_doors so both door paths are reached.

#include <cmath>
#include <cstdint>
#include <span>

#include "fuzz/contract.hpp"
#include "fuzz/memory_file.hpp"
#include "io/indoorgml.hpp"
#include "io/input_error.hpp"

namespace conicloc::fuzz {

inline void run_indoorgml(std::span<const std::uint8_t> input) {
  const MemoryFile file(input.data(), input.size());
  io::MapLoadOptions options;
  options.close_doors = (input.size() % 2) == 1;
  try {
    const io::LoadedMap loaded = io::load_indoorgml(file.path(), options);
    require(loaded.report.file_bytes == input.size(), "report.file_bytes is not the file size");
    require(std::isfinite(loaded.report.max_flatness_m), "max_flatness_m is not finite");
  } catch (const io::InputError&) {
    // The documented rejection (malformed XML, not IndoorGML, broken xlink, bad coordinates...).
  }
}

}  // namespace conicloc::fuzz
