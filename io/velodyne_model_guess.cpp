#include "io/velodyne_model_guess.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "io/open_capture.hpp"
#include "io/point_cloud2_msg.hpp"
#include "io/velodyne_packet.hpp"
#include "sensor/builtin_calibration.hpp"

namespace conicloc::io {

std::optional<sensor::SensorModel> model_from_packet_period(double period_us, bool dual,
                                                            std::uint8_t product_byte) {
  const double groups = dual ? 6.0 : 12.0;
  for (const auto model :
       {sensor::SensorModel::VLP16, sensor::SensorModel::HDL32E, sensor::SensorModel::VLP32C}) {
    const double expected_us = velodyne::packet_layout(model).block_period_us() * groups;
    if (std::abs(period_us - expected_us) < 0.1 * expected_us) {
      if (model == sensor::SensorModel::VLP16 &&
          product_byte == static_cast<std::uint8_t>(velodyne::ProductId::PuckHiRes)) {
        return sensor::SensorModel::PuckHiRes;
      }
      return model;
    }
  }
  return std::nullopt;
}

std::optional<ModelGuess> guess_model_from_capture(const std::string& path, std::uint16_t port,
                                                   std::size_t max_packets,
                                                   const std::string& topic) {
  // A bag of point clouds has no packets to time: the caller's default (or --model) holds.
  if (const auto bag = open_bag(path, topic); bag && is_point_cloud2_type(bag->topic.type)) {
    return std::nullopt;
  }
  const auto capture = open_capture(path, {.ports = {port}, .topic = topic});
  DatagramSource& reader = *capture;
  std::vector<double> periods_us;
  std::optional<std::uint32_t> previous_stamp;
  std::uint8_t product = 0;
  std::uint8_t mode = 0;
  std::size_t packets = 0;
  while (auto datagram = reader.next()) {
    if (datagram->payload.size() != velodyne::kDataPacketBytes) continue;
    const std::uint8_t* p = datagram->payload.data();
    if (p[0] != velodyne::kBlockFlag0 || p[1] != velodyne::kBlockFlag1) continue;
    const std::uint32_t stamp = velodyne::read_u32(p + velodyne::kTimestampOffset);
    product = p[velodyne::kProductIdOffset];
    mode = p[velodyne::kReturnModeOffset];
    if (previous_stamp && stamp > *previous_stamp) periods_us.push_back(stamp - *previous_stamp);
    previous_stamp = stamp;
    if (++packets >= max_packets) break;
  }
  const bool dual = mode == static_cast<std::uint8_t>(velodyne::ReturnMode::Dual);
  if (periods_us.size() >= 2) {
    std::nth_element(periods_us.begin(), periods_us.begin() + periods_us.size() / 2,
                     periods_us.end());
    const double median_us = periods_us[periods_us.size() / 2];
    if (const auto model = model_from_packet_period(median_us, dual, product)) {
      char text[160];
      std::snprintf(text, sizeof text, "packet period %.1f us, product byte 0x%02x, %s return",
                    median_us, product, velodyne::return_mode_name(mode).c_str());
      return ModelGuess{*model, text};
    }
  }
  if (const auto named = velodyne::model_from_product_id(product)) {
    return ModelGuess{*named, "product byte only (too few packets to time)"};
  }
  return std::nullopt;
}

}  // namespace conicloc::io
