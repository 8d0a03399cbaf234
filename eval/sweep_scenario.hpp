#pragma once
// The named scenarios of an evaluation sweep: how the sensor moves, what the world adds to the
// map, how the filter starts and whether it gets odometry. Plain settings; `conicloc evaluate`
// turns them into a simulation and a localization.

#include <string>
#include <vector>

namespace conicloc::eval {

enum class FilterStartMode {
  Tracking,  ///< around the first true pose (σ 0.2 m, 5°)
  Global,    ///< over the free space of every navigable cell
  Kidnap,    ///< confident (σ 0.1 m, 2°) at a pose 3 m and 90° off the truth: the filter must
             ///< notice it is lost and recover
};

struct Scenario {
  std::string name;
  std::string description;
  bool handheld = false;        ///< a walking person's hand-held sensor (sway), else a robot
  bool effects = true;          ///< false: exact ranges, the world is the map
  double range_noise_m = 0.03;  ///< σ
  int clutter_level = 1;        ///< 0 none … 3 heavy (furniture and people)
  double map_error_m = 0.02;    ///< σ of wall shifts and tilts
  FilterStartMode start = FilterStartMode::Tracking;
  /// The localizer gets the simulated (drifting) odometry; false: it must follow the motion from
  /// the scans alone (constant-velocity guess), as a hand-held sensor or a robot without wheel
  /// encoders does.
  bool odometry = true;
};

/// Every built-in scenario: robot, handheld, clean, clutter, map-error, global, kidnap, the
/// robustness corpus's robot-no-odom, handheld-no-odom, crowd, map-error-5cm, global-no-odom,
/// kidnap-no-odom, and global starts where scan and map disagree: global-crowd,
/// global-map-error.
const std::vector<Scenario>& builtin_scenarios();

/// The scenario called `name`; nullptr when there is none.
const Scenario* find_scenario(const std::string& name);

std::vector<std::string> scenario_names();

}  // namespace conicloc::eval
