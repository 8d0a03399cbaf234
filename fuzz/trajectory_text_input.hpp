#pragma once
// Fuzz driver: the line-based text readers: TUM trajectories / odometry (io::read_tum) and
// simulator waypoint files (sim::read_waypoints). Byte 0 picks the reader (even: TUM, odd:
// waypoints); the rest is the file text, read from a stream as from a file. Shared by
// fuzz/fuzz_trajectory_text.cpp and test/test_fuzz_regressions.cpp.
//
// Both readers document io::InputError (naming the line) as their only rejection; anything else
// is a finding. Accepted output is checked against the documented contract.

#include <cmath>
#include <cstdint>
#include <span>
#include <sstream>
#include <string>

#include "fuzz/contract.hpp"
#include "io/input_error.hpp"
#include "io/tum_trajectory.hpp"
#include "sim/waypoint_file.hpp"

namespace conicloc::fuzz {

inline void run_trajectory_text(std::span<const std::uint8_t> input) {
  if (input.empty()) return;
  std::istringstream text(std::string(input.begin() + 1, input.end()));
  try {
    if (input[0] % 2 == 0) {
      const auto poses = io::read_tum(text, "fuzz.tum");
      for (std::size_t i = 0; i < poses.size(); ++i) {
        require(std::isfinite(poses[i].time_s) && poses[i].pose.matrix().allFinite(),
                "read_tum accepted a non-finite pose");
        require(i == 0 || poses[i].time_s >= poses[i - 1].time_s,
                "read_tum accepted a decreasing timestamp");
      }
    } else {
      const auto waypoints = sim::read_waypoints(text, "fuzz.waypoints");
      require(!waypoints.empty(), "read_waypoints returned no waypoints without an error");
      for (const auto& waypoint : waypoints) {
        require(waypoint.floor_point.allFinite(), "read_waypoints accepted a non-finite point");
        require(!waypoint.yaw_rad || std::isfinite(*waypoint.yaw_rad),
                "read_waypoints accepted a non-finite yaw");
      }
    }
  } catch (const io::InputError&) {
    // The documented rejection: a malformed line, non-finite value, bad quaternion, no waypoints.
  }
}

}  // namespace conicloc::fuzz
