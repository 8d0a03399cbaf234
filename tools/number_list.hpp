#pragma once
// Comma-separated numbers from a command-line flag ("x,y,z,yaw_deg").

#include <string>
#include <vector>

namespace conicloc::tools {

/// Exactly `count` finite numbers; throws CLI::ValidationError naming `flag` otherwise.
std::vector<double> parse_numbers(const std::string& text, std::size_t count,
                                  const std::string& flag);

}  // namespace conicloc::tools
