#pragma once
// What `conicloc evaluate --sweep` runs: the cross product of buildings × scenarios × seeds (one
// simulated recording each) × models × particle counts × beam counts (one localization each).

#include <cstdint>
#include <string>
#include <vector>

namespace conicloc::eval {

struct SweepSpec {
  std::string name;                ///< "quick", "full" or the sweep file's path
  std::vector<std::string> maps;   ///< buildings besides --map (paths)
  std::vector<std::string> models; ///< observation model names
  std::vector<int> particles;      ///< maximum particle counts
  std::vector<int> beams;          ///< beams (conic-beam) / points (point-to-plane) per scan; 0: all
  std::vector<std::uint64_t> seeds;
  std::vector<std::string> scenarios;  ///< names from scenario_names()
  double duration_s = 15.0;            ///< simulated seconds per recording
  int threads = 0;                     ///< localizer threads; 0: all cores
  bool keep_captures = false;          ///< keep each recording's pcap in the output folder
};

/// A few minutes on 2 cores: every model at two particle counts, robot and hand-held.
SweepSpec quick_sweep();
/// Every scenario, three seeds, 100 … 20,000 particles and three beam counts: hours.
SweepSpec full_sweep();

/// Reads a sweep file: `key = value, value, …` per line, `#` starts a comment. Keys: maps, models,
/// particles, beams, seeds, scenarios, duration_s, threads, keep_captures; a key left out keeps
/// the quick sweep's value. Relative map paths are taken from the file's folder. Throws
/// io::InputError naming the file and line for an unknown key, a bad number, an unknown model or
/// scenario, or an empty list.
SweepSpec read_sweep_file(const std::string& path);

/// "quick", "full", or a sweep file.
SweepSpec resolve_sweep(const std::string& name_or_path);

}  // namespace conicloc::eval
