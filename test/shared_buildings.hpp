#pragma once
// The public IndoorGML models of ../shared/data/indoorgml (CONICLOC_SHARED_DATA), for tests that
// run on real buildings where that folder is present and skip where it is not.

#include <algorithm>
#include <filesystem>
#include <vector>

namespace conicloc::test {

/// The folder the models are read from.
inline std::filesystem::path shared_indoorgml_dir() {
  return std::filesystem::path(CONICLOC_SHARED_DATA) / "indoorgml";
}

/// Every .gml file of shared_indoorgml_dir(), sorted; empty when the folder is absent.
inline std::vector<std::filesystem::path> shared_indoorgml_models() {
  std::vector<std::filesystem::path> models;
  if (!std::filesystem::is_directory(shared_indoorgml_dir())) return models;
  for (const auto& entry : std::filesystem::directory_iterator(shared_indoorgml_dir())) {
    if (entry.path().extension() == ".gml") models.push_back(entry.path());
  }
  std::sort(models.begin(), models.end());
  return models;
}

}  // namespace conicloc::test
