#pragma once
// The runs of an evaluation sweep, in the order the sweep makes them: buildings × seeds ×
// scenarios (one simulated recording each) × localizer settings. Each run has a key that names it
// and an index, the same on every machine, so a sweep can be split into shards and merged again.

#include <cstdint>
#include <string>
#include <vector>

#include "eval/sweep_spec.hpp"

namespace conicloc::eval {

struct RunRecord;

/// One localizer configuration of a sweep.
struct LocalizerSetting {
  std::string model;
  int particles = 0;  ///< or kDefaultSetting
  int beams = 0;      ///< 0: all; or kDefaultSetting
};

/// Every (model, particles, beams) of the sweep, models outermost; conic-segment segments every
/// return, so it runs once per particle count (beams 0).
std::vector<LocalizerSetting> localizer_settings(const SweepSpec& spec);

/// What identifies one run of a sweep: the columns of runs.csv that name it.
struct RunKey {
  std::string building;  ///< as RunRecord::building
  std::string scenario;
  std::uint64_t seed = 0;
  std::string model;
  int particles = 0;
  int beams = 0;

  /// `building/scenario/sSEED/model/pPARTICLES/bBEAMS`, e.g.
  /// `example_building/robot/s1/conic-beam/p300/b300`.
  std::string text() const;
  auto operator<=>(const RunKey&) const = default;
};

RunKey key_of(const RunRecord& run);

/// A building of the sweep's list as the plan sees it.
struct PlannedBuilding {
  std::string name;  ///< the building's name; for one drawn anew per seed, the generator's KIND
  bool per_seed = false;  ///< named `KIND-sSEED` for each sweep seed
};

/// The name a building has for sweep seed `seed`.
std::string building_name(const PlannedBuilding& building, std::uint64_t seed);

/// The name of the recording simulated for (building, scenario, seed), `BUILDING-SCENARIO-sSEED`:
/// the stem of its capture, truth, odometry and map-fit files.
std::string recording_name(const std::string& building, const std::string& scenario,
                           std::uint64_t seed);

/// What follows a recording's name in its files' names: the one spelling its writer (the sweep's
/// simulation) and its readers (scoring, plots, merges) share.
inline constexpr char kCaptureSuffix[] = ".pcap";
inline constexpr char kTruthSuffix[] = ".truth.tum";
inline constexpr char kOdometrySuffix[] = ".odom.tum";
/// The poses the map gives the scans (sim/map_fit.hpp), written only for a recording with map
/// error.
inline constexpr char kMapFitSuffix[] = ".map-fit.tum";

/// Every run of the sweep, in the sweep's order; a run's index in this list is its index.
std::vector<RunKey> plan_runs(const std::vector<PlannedBuilding>& buildings, const SweepSpec& spec);

}  // namespace conicloc::eval
