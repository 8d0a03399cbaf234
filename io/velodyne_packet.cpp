#include "io/velodyne_packet.hpp"

#include <cstdio>

namespace conicloc::io::velodyne {

PacketLayout packet_layout(sensor::SensorModel model) {
  PacketLayout layout;
  switch (model) {
    case sensor::SensorModel::VLP16:
    case sensor::SensorModel::PuckLite:
    case sensor::SensorModel::PuckHiRes:
      // VLP-16 manual 9.5: 16 firings 2.304 µs apart, a sequence every 55.296 µs.
      break;
    case sensor::SensorModel::HDL32E:
      // HDL-32E manual: 32 lasers fired one by one, 1.152 µs apart; 46.08 µs per block.
      layout.channels = 32;
      layout.sequences_per_block = 1;
      layout.channel_spacing_us = 1.152;
      layout.sequence_period_us = 46.08;
      break;
    case sensor::SensorModel::VLP32C:
      // VLP-32C manual: lasers fired in pairs, 2.304 µs apart; 55.296 µs per sequence.
      layout.channels = 32;
      layout.sequences_per_block = 1;
      layout.channels_per_slot = 2;
      layout.distance_unit_m = 0.004;
      break;
  }
  return layout;
}

ProductId product_id(sensor::SensorModel model) {
  switch (model) {
    case sensor::SensorModel::VLP16:
    case sensor::SensorModel::PuckLite:
      return ProductId::VLP16;
    case sensor::SensorModel::PuckHiRes:
      return ProductId::PuckHiRes;
    case sensor::SensorModel::HDL32E:
      return ProductId::HDL32E;
    case sensor::SensorModel::VLP32C:
      return ProductId::VLP32C;
  }
  return ProductId::VLP16;
}

std::optional<sensor::SensorModel> model_from_product_id(std::uint8_t byte) {
  switch (byte) {
    case static_cast<std::uint8_t>(ProductId::HDL32E):
      return sensor::SensorModel::HDL32E;
    case static_cast<std::uint8_t>(ProductId::VLP16):
      return sensor::SensorModel::VLP16;
    case static_cast<std::uint8_t>(ProductId::PuckHiRes):
      return sensor::SensorModel::PuckHiRes;
    case static_cast<std::uint8_t>(ProductId::VLP32C):
      return sensor::SensorModel::VLP32C;
    default:
      return std::nullopt;
  }
}

std::string return_mode_name(std::uint8_t byte) {
  switch (byte) {
    case static_cast<std::uint8_t>(ReturnMode::Strongest):
      return "strongest";
    case static_cast<std::uint8_t>(ReturnMode::Last):
      return "last";
    case static_cast<std::uint8_t>(ReturnMode::Dual):
      return "dual";
    default: {
      char text[32];
      std::snprintf(text, sizeof text, "unknown(0x%02x)", byte);
      return text;
    }
  }
}

const char* return_label_name(ReturnLabel label) {
  switch (label) {
    case ReturnLabel::Strongest:
      return "strongest";
    case ReturnLabel::Last:
      return "last";
    case ReturnLabel::DualLast:
      return "dual_last";
    case ReturnLabel::DualStrongest:
      return "dual_strongest";
    case ReturnLabel::DualBoth:
      return "dual_both";
  }
  return "strongest";
}

}  // namespace conicloc::io::velodyne
