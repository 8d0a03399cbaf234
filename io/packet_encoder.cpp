#include "io/packet_encoder.hpp"

#include <cmath>

namespace conicloc::io {
namespace {

constexpr double kRadToCentiDeg = 18000.0 / M_PI;

std::uint16_t distance_units(double range_m, double unit_m) {
  if (!std::isfinite(range_m) || range_m <= 0.0) return 0;
  const double units = std::round(range_m / unit_m);
  if (units >= 65535.0) return 0;  // beyond what 16 bits of 2 mm hold: the sensor reports nothing
  return static_cast<std::uint16_t>(units);
}

}  // namespace

std::uint16_t velodyne_azimuth_from_rad(double azimuth_rad) {
  // α = −θ (Velodyne counts clockwise seen from above), wrapped into [0, 36000).
  double centideg = std::round(-azimuth_rad * kRadToCentiDeg);
  centideg = std::fmod(centideg, static_cast<double>(velodyne::kAzimuthUnitsPerTurn));
  if (centideg < 0) centideg += velodyne::kAzimuthUnitsPerTurn;
  const auto units = static_cast<int>(centideg);
  return static_cast<std::uint16_t>(units % velodyne::kAzimuthUnitsPerTurn);
}

std::uint32_t microseconds_past_hour(double time_s) {
  double seconds = std::fmod(time_s, 3600.0);
  if (seconds < 0) seconds += 3600.0;
  const auto us = static_cast<std::uint64_t>(std::llround(seconds * 1e6));
  return static_cast<std::uint32_t>(us % velodyne::kMicrosecondsPerHour);
}

PacketEncoder::PacketEncoder(EncoderConfig config)
    : config_(config), layout_(velodyne::packet_layout(config.model)) {}

int PacketEncoder::sequences_per_packet() const {
  const int blocks = config_.return_mode == velodyne::ReturnMode::Dual
                         ? velodyne::kBlocksPerPacket / 2
                         : velodyne::kBlocksPerPacket;
  return blocks * layout_.sequences_per_block;
}

void PacketEncoder::write_sequence(const FiringSequence& sequence, int slot) {
  const bool dual = config_.return_mode == velodyne::ReturnMode::Dual;
  const int block_slot = slot / layout_.sequences_per_block;  // block (pair, in dual mode)
  const int within = slot % layout_.sequences_per_block;
  const int first_block = dual ? 2 * block_slot : block_slot;
  const int block_count = dual ? 2 : 1;
  for (int b = 0; b < block_count; ++b) {
    std::uint8_t* block = current_.payload.data() + velodyne::block_offset(first_block + b);
    if (within == 0) {
      block[0] = velodyne::kBlockFlag0;
      block[1] = velodyne::kBlockFlag1;
      velodyne::write_u16(block + 2, velodyne_azimuth_from_rad(sequence.azimuth_rad));
    }
    // Dual: even block = last echo (range_m), odd block = strongest (second_range_m, or the same
    // echo again when there is only one).
    const bool second = b == 1 && dual;
    for (int k = 0; k < layout_.channels; ++k) {
      double range = sequence.range_m[k];
      std::uint8_t intensity = sequence.intensity[k];
      if (second && distance_units(sequence.second_range_m[k], layout_.distance_unit_m) != 0) {
        range = sequence.second_range_m[k];
        intensity = sequence.second_intensity[k];
      }
      std::uint8_t* record =
          block + 4 +
          static_cast<std::size_t>(within * layout_.channels + k) * velodyne::kRecordBytes;
      velodyne::write_u16(record, distance_units(range, layout_.distance_unit_m));
      record[2] = intensity;
    }
  }
}

void PacketEncoder::add(const FiringSequence& sequence) {
  if (last_) last_step_rad_ = sequence.azimuth_rad - last_->azimuth_rad;
  if (pending_ == 0) {
    current_ = EncodedPacket{};
    current_.time_s = sequence.time_s;
    velodyne::write_u32(current_.payload.data() + velodyne::kTimestampOffset,
                        microseconds_past_hour(sequence.time_s));
    current_.payload[velodyne::kReturnModeOffset] = static_cast<std::uint8_t>(config_.return_mode);
    current_.payload[velodyne::kProductIdOffset] =
        config_.product_id.value_or(static_cast<std::uint8_t>(velodyne::product_id(config_.model)));
  }
  write_sequence(sequence, pending_);
  last_ = sequence;
  if (++pending_ == sequences_per_packet()) {
    done_.push_back(current_);
    pending_ = 0;
  }
}

void PacketEncoder::flush() {
  while (pending_ != 0) {
    FiringSequence empty;
    empty.azimuth_rad = last_->azimuth_rad + last_step_rad_;
    empty.time_s = last_->time_s + layout_.sequence_period_us * 1e-6;
    add(empty);
  }
}

std::vector<EncodedPacket> PacketEncoder::take_packets() {
  std::vector<EncodedPacket> out;
  out.swap(done_);
  return out;
}

}  // namespace conicloc::io
