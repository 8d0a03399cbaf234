#pragma once
// Decodes Velodyne data packets into points (one per laser record, no-returns included), with the
// firing time and azimuth of every laser interpolated from the packet's block azimuths.
//
// Azimuth: each block stores the azimuth α of its first firing (clockwise, 0.01°); laser k of
// sequence s fires at α + Δ·t(s, k)/T, where t is the firing offset of the manual's timing table,
// T the block period and Δ the mean block step of the packet (first to last block, kept to 0.001°).
// Our azimuth is θ = −α + (the laser's azimuth offset), REP-103. Hot loop: cos/sin of α from a
// table over 36000 hundredths of a degree, cos/sin of the per-laser increment from a table per
// 0.001° of step, one complex product per point; no trig per point. Time: packet_time_s (the
// caller's unwrapped device time of the packet's first firing) plus the firing offset. Dual return:
// see velodyne::ReturnLabel; the pair is emitted last then strongest, an identical pair once.
//
// Example:
//   io::VelodyneDecoder decoder(sensor::builtin_calibration(sensor::SensorModel::VLP16));
//   std::vector<io::DecodedPoint> points;
//   if (decoder.check(payload) == io::PacketCheck::Ok) decoder.decode(payload, t_s, points);

#include <cstdint>
#include <span>
#include <vector>

#include "io/velodyne_packet.hpp"
#include "sensor/laser_calibration.hpp"

namespace conicloc::io {

struct DecodedPoint {
  double time_s = 0.0;              ///< firing time, packet_time_s + firing offset
  float x_m = 0, y_m = 0, z_m = 0;  ///< sensor frame (REP-103), (0,0,o_k) + r·d_k(θ)
  float range_m = 0;                ///< 0 = no return
  float azimuth_rad = 0;  ///< θ in [0, 2π), counter-clockwise from x, laser offset included
  std::uint16_t firing_azimuth_cdeg = 0;  ///< Velodyne α of the firing (rounded), for rotation cuts
  std::uint8_t intensity = 0;
  std::uint8_t channel = 0;
  velodyne::ReturnLabel label = velodyne::ReturnLabel::Strongest;
};

/// Why a data payload cannot be decoded (checked per packet, before decoding).
enum class PacketCheck : std::uint8_t {
  Ok,
  WrongSize,     ///< not 1206 bytes
  BadBlockFlag,  ///< a block does not start with 0xFF 0xEE
  AllZero,       ///< all bytes zero (a blank packet; one with valid blocks and no returns is Ok)
  AzimuthOutOfRange,  ///< a block azimuth > 36000 (36000 itself is read as 0)
  AzimuthJump,        ///< blocks more than max_block_step apart (or dual pair azimuths differ)
  AzimuthRepeat,      ///< consecutive blocks at the same azimuth (not a dual pair)
  UnknownReturnMode,  ///< factory byte 1204 not 0x37/0x38/0x39
  // Found by the stream, comparing with the previous good packet:
  Duplicate,      ///< same timestamp and azimuth as the previous packet
  TimeBackwards,  ///< device time earlier than the previous packet's (not an hourly wrap)
};
inline constexpr std::size_t kPacketCheckCount = 10;

const char* packet_check_name(PacketCheck check);

class VelodyneDecoder {
 public:
  /// `max_block_step_cdeg`: largest plausible block-to-block azimuth step (2° ≫ 0.8° at 1200 rpm).
  explicit VelodyneDecoder(const sensor::LaserCalibration& calibration,
                           int max_block_step_cdeg = 200);

  PacketCheck check(std::span<const std::uint8_t> payload) const;

  /// Appends the points of a payload that passed check(); returns how many. Precondition: check()
  /// returned Ok.
  std::size_t decode(std::span<const std::uint8_t> payload, double packet_time_s,
                     std::vector<DecodedPoint>& out) const;

  const sensor::LaserCalibration& calibration() const { return calibration_; }
  const velodyne::PacketLayout& layout() const { return layout_; }

  static std::uint32_t timestamp_us(std::span<const std::uint8_t> payload) {
    return velodyne::read_u32(payload.data() + velodyne::kTimestampOffset);
  }
  static std::uint8_t return_mode_byte(std::span<const std::uint8_t> payload) {
    return payload[velodyne::kReturnModeOffset];
  }
  static std::uint8_t product_byte(std::span<const std::uint8_t> payload) {
    return payload[velodyne::kProductIdOffset];
  }

 private:
  struct LaserTerms {
    float cos_elevation, sin_elevation, vertical_offset_m, range_offset_m;
  };
  struct Rotation {
    float cos_a, sin_a;
  };
  Rotation increment(int step_cdeg, int slot) const;

  sensor::LaserCalibration calibration_;
  velodyne::PacketLayout layout_;
  int max_block_step_cdeg_;
  int slots_;  ///< sequences_per_block × channels
  std::vector<LaserTerms> lasers_;
  std::vector<float> slot_fraction_;    ///< firing offset / block period, per slot
  std::vector<float> slot_offset_rad_;  ///< laser azimuth offset, per slot
  std::vector<double> slot_time_s_;     ///< firing offset in seconds, per slot
  std::vector<Rotation> turn_;          ///< cos/sin of α, per 0.01°
  std::vector<Rotation> increments_;    ///< [step][slot] cos/sin of ψ = −Δ·f + offset
};

}  // namespace conicloc::io
