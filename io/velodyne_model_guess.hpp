#pragma once
// Which Velodyne model sent a stream, from packet timing rather than the product byte (old VLP-16
// firmware writes 0x21, the HDL-32E's byte). A packet holds 12 blocks (6 pairs in dual mode); a
// block lasts 110.592 µs on the 16-laser Pucks, 46.08 µs on the HDL-32E, 55.296 µs on the VLP-32C.
//
// Example:
//   auto guess = io::guess_model_from_capture("run.pcap", 2368);
//   if (guess) spdlog::info("{} ({})", sensor::sensor_model_name(guess->model), guess->reason);

#include <cstdint>
#include <optional>
#include <string>

#include "sensor/laser_calibration.hpp"

namespace conicloc::io {

/// The model whose packet period (12 blocks, or 6 pairs when `dual`) is within 10 % of
/// `period_us`; among the 16-laser models the product byte 0x24 selects the Puck Hi-Res.
std::optional<sensor::SensorModel> model_from_packet_period(double period_us, bool dual,
                                                            std::uint8_t product_byte);

struct ModelGuess {
  sensor::SensorModel model = sensor::SensorModel::VLP16;
  std::string reason;  ///< what it was decided from, for logs
};

/// Reads up to `max_packets` data packets of a capture (any format of io/open_capture.hpp; `topic`
/// picks a bag's topic); nullopt if it holds fewer than 3 good ones and no known product byte.
/// Throws InputError when the file is not a capture.
std::optional<ModelGuess> guess_model_from_capture(const std::string& path, std::uint16_t port,
                                                   std::size_t max_packets = 200,
                                                   const std::string& topic = "");

}  // namespace conicloc::io
