#include "io/velodyne_decoder.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace conicloc::io {
namespace {

constexpr double kCentiDegToRad = M_PI / 18000.0;
constexpr float kTwoPi = static_cast<float>(2.0 * M_PI);
// The block step is the packet's mean (first to last block), kept to 0.001°: quantising it to
// 0.01° would cost up to 0.01° at the end of a block.
constexpr int kStepSubdivisions = 10;

// Some firmware writes 36000 for 0 at the wrap; it is read as 0.
int block_azimuth(const std::uint8_t* payload, int block) {
  const int azimuth = velodyne::read_u16(payload + velodyne::block_offset(block) + 2);
  return azimuth == velodyne::kAzimuthUnitsPerTurn ? 0 : azimuth;
}

// Step from `from` to `to` in hundredths of a degree, wrapped into [−18000, 18000).
int wrapped_step(int from, int to) {
  int step = to - from;
  if (step >= 18000) step -= 36000;
  if (step < -18000) step += 36000;
  return step;
}

}  // namespace

const char* packet_check_name(PacketCheck check) {
  switch (check) {
    case PacketCheck::Ok:
      return "ok";
    case PacketCheck::WrongSize:
      return "wrong_size";
    case PacketCheck::BadBlockFlag:
      return "bad_block_flag";
    case PacketCheck::AllZero:
      return "all_zero";
    case PacketCheck::AzimuthOutOfRange:
      return "azimuth_out_of_range";
    case PacketCheck::AzimuthJump:
      return "azimuth_jump";
    case PacketCheck::AzimuthRepeat:
      return "azimuth_repeat";
    case PacketCheck::UnknownReturnMode:
      return "unknown_return_mode";
    case PacketCheck::Duplicate:
      return "duplicate";
    case PacketCheck::TimeBackwards:
      return "time_backwards";
  }
  return "?";
}

VelodyneDecoder::VelodyneDecoder(const sensor::LaserCalibration& calibration,
                                 int max_block_step_cdeg)
    : calibration_(calibration),
      layout_(velodyne::packet_layout(calibration.model)),
      max_block_step_cdeg_(max_block_step_cdeg),
      slots_(layout_.sequences_per_block * layout_.channels) {
  if (calibration_.ring_count() != layout_.channels) {
    throw std::invalid_argument("calibration has " + std::to_string(calibration_.ring_count()) +
                                " lasers, the model fires " + std::to_string(layout_.channels));
  }
  for (const auto& laser : calibration_.lasers) {
    lasers_.push_back({static_cast<float>(std::cos(laser.elevation_rad)),
                       static_cast<float>(std::sin(laser.elevation_rad)),
                       static_cast<float>(laser.vertical_offset_m),
                       static_cast<float>(laser.range_offset_m)});
  }
  for (int s = 0; s < layout_.sequences_per_block; ++s) {
    for (int k = 0; k < layout_.channels; ++k) {
      const double offset_us = layout_.firing_offset_us(s, k);
      slot_fraction_.push_back(static_cast<float>(offset_us / layout_.block_period_us()));
      slot_offset_rad_.push_back(static_cast<float>(calibration_.lasers[k].azimuth_offset_rad));
      slot_time_s_.push_back(offset_us * 1e-6);
    }
  }
  turn_.resize(velodyne::kAzimuthUnitsPerTurn);
  for (int a = 0; a < velodyne::kAzimuthUnitsPerTurn; ++a) {
    turn_[a] = {static_cast<float>(std::cos(a * kCentiDegToRad)),
                static_cast<float>(std::sin(a * kCentiDegToRad))};
  }
  const int steps = max_block_step_cdeg_ * kStepSubdivisions;
  increments_.resize(static_cast<std::size_t>(steps + 1) * slots_);
  for (int step = 0; step <= steps; ++step) {
    for (int slot = 0; slot < slots_; ++slot) {
      const double psi = -step * (kCentiDegToRad / kStepSubdivisions) * slot_fraction_[slot] +
                         slot_offset_rad_[slot];
      increments_[static_cast<std::size_t>(step) * slots_ + slot] = {
          static_cast<float>(std::cos(psi)), static_cast<float>(std::sin(psi))};
    }
  }
}

VelodyneDecoder::Rotation VelodyneDecoder::increment(int step_cdeg, int slot) const {
  return increments_[static_cast<std::size_t>(step_cdeg) * slots_ + slot];
}

PacketCheck VelodyneDecoder::check(std::span<const std::uint8_t> payload) const {
  if (payload.size() != velodyne::kDataPacketBytes) return PacketCheck::WrongSize;
  const std::uint8_t* p = payload.data();
  if (std::all_of(payload.begin(), payload.end(), [](std::uint8_t b) { return b == 0; })) {
    return PacketCheck::AllZero;  // a blank packet (some switches and recorders emit them)
  }
  const std::uint8_t mode = p[velodyne::kReturnModeOffset];
  const bool dual = mode == static_cast<std::uint8_t>(velodyne::ReturnMode::Dual);
  // A packet with valid blocks but no distance anywhere is good data: the sensor faced open space
  // (a doorway to outside, the sky), and its no-returns must reach the scan, not be rejected.
  for (int b = 0; b < velodyne::kBlocksPerPacket; ++b) {
    const std::uint8_t* block = p + velodyne::block_offset(b);
    if (block[0] != velodyne::kBlockFlag0 || block[1] != velodyne::kBlockFlag1) {
      return PacketCheck::BadBlockFlag;
    }
  }
  if (mode != static_cast<std::uint8_t>(velodyne::ReturnMode::Strongest) &&
      mode != static_cast<std::uint8_t>(velodyne::ReturnMode::Last) && !dual) {
    return PacketCheck::UnknownReturnMode;
  }
  const int stride = dual ? 2 : 1;
  for (int b = 0; b < velodyne::kBlocksPerPacket; ++b) {
    if (velodyne::read_u16(p + velodyne::block_offset(b) + 2) > velodyne::kAzimuthUnitsPerTurn) {
      return PacketCheck::AzimuthOutOfRange;
    }
  }
  for (int b = 0; b + stride < velodyne::kBlocksPerPacket; b += stride) {
    if (dual && block_azimuth(p, b) != block_azimuth(p, b + 1)) return PacketCheck::AzimuthJump;
    const int step = wrapped_step(block_azimuth(p, b), block_azimuth(p, b + stride));
    if (step == 0) return PacketCheck::AzimuthRepeat;
    if (step < 0 || step > max_block_step_cdeg_) return PacketCheck::AzimuthJump;
  }
  return PacketCheck::Ok;
}

std::size_t VelodyneDecoder::decode(std::span<const std::uint8_t> payload, double packet_time_s,
                                    std::vector<DecodedPoint>& out) const {
  const std::uint8_t* p = payload.data();
  const std::uint8_t mode = p[velodyne::kReturnModeOffset];
  const bool dual = mode == static_cast<std::uint8_t>(velodyne::ReturnMode::Dual);
  const velodyne::ReturnLabel single_label =
      mode == static_cast<std::uint8_t>(velodyne::ReturnMode::Last)
          ? velodyne::ReturnLabel::Last
          : velodyne::ReturnLabel::Strongest;
  const int stride = dual ? 2 : 1;
  const int groups = velodyne::kBlocksPerPacket / stride;
  const std::size_t first = out.size();
  out.resize(first + static_cast<std::size_t>(groups) * slots_ * stride);
  DecodedPoint* dst = out.data() + first;
  const double block_period_s = layout_.block_period_us() * 1e-6;
  const int channels = layout_.channels;
  const auto distance_unit_m = static_cast<float>(layout_.distance_unit_m);

  // Mean block step over the packet, in 0.001°; check() guarantees 0 < step ≤ max per block.
  const int span = wrapped_step(block_azimuth(p, 0), block_azimuth(p, (groups - 1) * stride));
  int step =
      static_cast<int>(std::lround(static_cast<double>(span) * kStepSubdivisions / (groups - 1)));
  step = std::clamp(step, 0, max_block_step_cdeg_ * kStepSubdivisions);
  const float step_rad = static_cast<float>(step * kCentiDegToRad / kStepSubdivisions);
  const Rotation* incr = &increments_[static_cast<std::size_t>(step) * slots_];
  for (int g = 0; g < groups; ++g) {
    const int block = g * stride;
    const int azimuth = block_azimuth(p, block);
    const Rotation base = turn_[azimuth];
    const double group_time_s = packet_time_s + g * block_period_s;
    const std::uint8_t* records = p + velodyne::block_offset(block) + 4;
    const std::uint8_t* records2 = dual ? records + velodyne::kBlockBytes : nullptr;

    for (int slot = 0; slot < slots_; ++slot) {
      const int channel = slot % channels;
      const LaserTerms& laser = lasers_[channel];
      // θ = −α + ψ: cos θ = cos α cos ψ + sin α sin ψ, sin θ = cos α sin ψ − sin α cos ψ.
      const float cos_t = base.cos_a * incr[slot].cos_a + base.sin_a * incr[slot].sin_a;
      const float sin_t = base.cos_a * incr[slot].sin_a - base.sin_a * incr[slot].cos_a;
      const float alpha_rad =
          static_cast<float>(azimuth * kCentiDegToRad) + step_rad * slot_fraction_[slot];
      float theta = slot_offset_rad_[slot] - alpha_rad;
      theta += theta < 0 ? kTwoPi : 0.0f;
      theta += theta < 0 ? kTwoPi : 0.0f;
      theta -= theta >= kTwoPi ? kTwoPi : 0.0f;
      const int firing_cdeg =
          (azimuth + static_cast<int>(step * slot_fraction_[slot] / kStepSubdivisions + 0.5f)) %
          velodyne::kAzimuthUnitsPerTurn;
      const double time_s = group_time_s + slot_time_s_[slot];

      auto emit = [&](const std::uint8_t* record, velodyne::ReturnLabel label) {
        // r = r_raw + d_k for a return; a raw 0 (no return) stays 0.
        const std::uint16_t raw = velodyne::read_u16(record);
        const float range =
            raw > 0 ? static_cast<float>(raw) * distance_unit_m + laser.range_offset_m : 0.0f;
        const float horizontal = range * laser.cos_elevation;
        dst->time_s = time_s;
        dst->x_m = horizontal * cos_t;
        dst->y_m = horizontal * sin_t;
        dst->z_m = range > 0 ? range * laser.sin_elevation + laser.vertical_offset_m : 0.0f;
        dst->range_m = range;
        dst->azimuth_rad = theta;
        dst->firing_azimuth_cdeg = static_cast<std::uint16_t>(firing_cdeg);
        dst->intensity = record[2];
        dst->channel = static_cast<std::uint8_t>(channel);
        dst->label = label;
        ++dst;
      };
      const std::uint8_t* record = records + slot * velodyne::kRecordBytes;
      if (!dual) {
        emit(record, single_label);
        continue;
      }
      const std::uint8_t* record2 = records2 + slot * velodyne::kRecordBytes;
      if (record[0] == record2[0] && record[1] == record2[1] && record[2] == record2[2]) {
        emit(record, velodyne::ReturnLabel::DualBoth);
      } else {
        emit(record, velodyne::ReturnLabel::DualLast);
        emit(record2, velodyne::ReturnLabel::DualStrongest);
      }
    }
  }
  const auto count = static_cast<std::size_t>(dst - (out.data() + first));
  out.resize(first + count);
  return count;
}

}  // namespace conicloc::io
