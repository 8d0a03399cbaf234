#include "eval/sweep_scenario.hpp"

namespace conicloc::eval {

const std::vector<Scenario>& builtin_scenarios() {
  static const std::vector<Scenario> scenarios = [] {
    std::vector<Scenario> all;
    all.push_back(
        {.name = "robot", .description = "robot, 3 cm noise, light clutter, 2 cm map error"});
    all.push_back({.name = "handheld",
                   .description = "hand-held sensor carried by a walking person (sway)",
                   .handheld = true});
    all.push_back({.name = "clean",
                   .description = "robot, exact ranges, the world is the map",
                   .effects = false,
                   .range_noise_m = 0.0,
                   .clutter_level = 0,
                   .map_error_m = 0.0});
    all.push_back({.name = "clutter",
                   .description = "robot, heavy clutter: furniture and people the map lacks",
                   .clutter_level = 3});
    all.push_back({.name = "map-error",
                   .description = "robot, walls shifted and tilted by 5 cm (σ)",
                   .map_error_m = 0.05});
    all.push_back({.name = "global",
                   .description = "robot, global start over all storeys",
                   .start = FilterStartMode::Global});
    all.push_back({.name = "kidnap",
                   .description = "robot, filter starts confident 3 m and 90° off the truth",
                   .start = FilterStartMode::Kidnap});
    // The robustness corpus (issue 14): the targets hold with and without odometry, so every
    // motion and every start is also run from the scans alone.
    all.push_back(
        {.name = "robot-no-odom", .description = "robot without odometry", .odometry = false});
    all.push_back({.name = "handheld-no-odom",
                   .description = "hand-held at 1.4 m, walking sway, without odometry",
                   .handheld = true,
                   .odometry = false});
    all.push_back({.name = "crowd",
                   .description = "robot among heavy clutter and walking people",
                   .clutter_level = 3});
    all.push_back({.name = "map-error-5cm",
                   .description = "robot, walls shifted and tilted by 5 cm (σ)",
                   .map_error_m = 0.05});
    all.push_back({.name = "global-no-odom",
                   .description = "robot without odometry, global start over all storeys",
                   .start = FilterStartMode::Global,
                   .odometry = false});
    all.push_back({.name = "kidnap-no-odom",
                   .description = "robot without odometry, filter starts confident 3 m and 90° "
                                  "off the truth",
                   .start = FilterStartMode::Kidnap,
                   .odometry = false});
    // A global start where the scan and the map disagree: the walls the first scans see are
    // partly hidden by furniture and people the map lacks, or stand off their modelled place.
    // What a start's floor-plan search must survive in a building nobody mapped exactly.
    all.push_back({.name = "global-crowd",
                   .description = "robot among heavy clutter and walking people, global start",
                   .clutter_level = 3,
                   .start = FilterStartMode::Global});
    all.push_back({.name = "global-map-error",
                   .description = "robot, walls shifted and tilted by 5 cm (σ), global start",
                   .map_error_m = 0.05,
                   .start = FilterStartMode::Global});
    return all;
  }();
  return scenarios;
}

const Scenario* find_scenario(const std::string& name) {
  for (const auto& scenario : builtin_scenarios()) {
    if (scenario.name == name) return &scenario;
  }
  return nullptr;
}

std::vector<std::string> scenario_names() {
  std::vector<std::string> names;
  for (const auto& scenario : builtin_scenarios()) names.push_back(scenario.name);
  return names;
}

}  // namespace conicloc::eval
