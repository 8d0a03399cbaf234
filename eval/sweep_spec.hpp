#pragma once
// What `conicloc evaluate --sweep` runs: the cross product of buildings × scenarios × seeds (one
// simulated recording each) × models × particle counts × beam counts (one localization each).

#include <cstdint>
#include <string>
#include <vector>

namespace conicloc::eval {

/// A particles or beams value of `default`: leave the localizer's setting as `conicloc localize`
/// has it without options (particles: the initial, minimum and maximum counts; beams: the
/// model's beams or points per scan).
inline constexpr int kDefaultSetting = -1;

struct SweepSpec {
  std::string name;  ///< "quick", "full", "robustness", "scale" or the sweep file's path
  /// Buildings besides --map: IndoorGML paths, `generated:KIND:SEED` (one fixed generated
  /// building) or `generated:KIND` (a different building per sweep seed, drawn with that seed).
  std::vector<std::string> maps;
  std::vector<std::string> models;  ///< observation model names
  std::vector<int> particles;       ///< maximum particle counts, or kDefaultSetting
  /// Beams (conic-beam) / points (point-to-plane) per scan; 0: all; kDefaultSetting.
  std::vector<int> beams;
  std::vector<std::uint64_t> seeds;
  std::vector<std::string> scenarios;  ///< names from scenario_names()
  double duration_s = 15.0;            ///< simulated seconds per recording
  int threads = 0;                     ///< localizer threads; 0: all cores
  bool keep_captures = false;          ///< keep each recording's pcap in the output folder
  std::vector<std::string> warnings;   ///< what the sweep had to leave out, for the log
};

/// A few minutes on 2 cores: every model at two particle counts, robot and hand-held.
SweepSpec quick_sweep();
/// Every scenario, three seeds, 100 … 20,000 particles and three beam counts: hours.
SweepSpec full_sweep();
/// Issue 14's corpus, hours: besides --map, every .gml file of `public_models_dir` (the public
/// IndoorGML models; a warning when the folder is absent) and the generated corridor, wings,
/// hall and storeys buildings, a new one per seed; robot and hand-held with and without
/// odometry, crowd, 5 cm map error, global start and kidnap (each also without odometry); seeds
/// 1–5; the three models at `conicloc localize`'s default particles and beams; 30 s each.
SweepSpec robustness_sweep(const std::string& public_models_dir);

/// Issue 15's cost against building size, about 8 minutes on a 2-core machine: generated storeys buildings (seed 1)
/// of 1, 2, 5 and 10 storeys with one floor plate, of 2 and 4 plates with one storey, and of 10
/// storeys × 4 plates; robot tracking and a global start, both with odometry; conic-beam at its
/// defaults; seeds 1–5; 20 s each. Its report's scale.md holds the table.
SweepSpec scale_sweep();

/// Reads a sweep file: `key = value, value, …` per line, `#` starts a comment. Keys: base
/// (quick, full, robustness or scale: the sweep the other keys modify; quick when left out), maps,
/// models, particles, beams (both also `default`), seeds, scenarios, duration_s, threads,
/// keep_captures. Relative map paths are taken from the file's folder; `maps` may be empty (only
/// --map). Throws io::InputError naming the file and line for an unknown key, a bad number, an
/// unknown model, scenario or base, or an empty list.
SweepSpec read_sweep_file(const std::string& path, const std::string& public_models_dir = {});

/// "quick", "full", "robustness", "scale", or a sweep file.
SweepSpec resolve_sweep(const std::string& name_or_path, const std::string& public_models_dir = {});

/// The spec as a sweep file that read_sweep_file() reads back to the same spec: every key, maps
/// as given (absolute paths read back unchanged). A shard folder keeps its sweep in this form.
std::string sweep_file_text(const SweepSpec& spec);

/// A map entry that names a generated building (`generated:…`) rather than a file.
bool is_generated_map(const std::string& map);

/// "default" for kDefaultSetting, else the number.
std::string setting_text(int value);
/// As setting_text, and "all" for 0 beams.
std::string beams_text(int beams);

}  // namespace conicloc::eval
