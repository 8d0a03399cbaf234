#pragma once
// `--sensor [ADDR:]PORT`: which sensor of a capture holding several, by the UDP port its data
// packets go to and, where two share a port, the IPv4 address they come from.
//
// Example:
//   io::StreamConfig stream;
//   apply_sensor_option("192.168.1.202:2368", "--second-sensor", stream);
//   // stream.data_port == 2368, stream.source_address == 0xC0A801CA

#include <string>

#include "io/velodyne_stream.hpp"

namespace conicloc::tools {

/// Sets `stream`'s data port and source address (0 without ADDR) from `text`. Throws
/// io::InputError naming `flag` for a malformed text, an unknown host or port 0.
void apply_sensor_option(const std::string& text, const std::string& flag,
                         io::StreamConfig& stream);

/// "192.168.1.201:2368", or ":2368" for any sender.
std::string sensor_text(const io::StreamConfig& stream);

}  // namespace conicloc::tools
