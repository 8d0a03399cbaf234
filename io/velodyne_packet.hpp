#pragma once
// The byte layout of Velodyne UDP packets (VLP-16 / Puck / HDL-32E / VLP-32C user manuals).
//
// Data packet (UDP port 2368), 1206-byte payload:
//   12 blocks × 100 bytes: flag 0xFF 0xEE, azimuth (uint16 LE, clockwise hundredths of a degree),
//                          32 records × (distance uint16 LE in 2 mm units, reflectivity uint8)
//   timestamp  (uint32 LE at byte 1200): microseconds past the top of the hour of the first firing
//   factory    (byte 1204 return mode 0x37/0x38/0x39, byte 1205 product id)
// A block holds `sequences_per_block` firing sequences of `channels` lasers: 2 × 16 on VLP-16 and
// Pucks, 1 × 32 on HDL-32E and VLP-32C. In dual-return mode blocks come in pairs with the same
// azimuth: the even block holds the last return, the odd block the strongest (the second strongest
// when strongest and last coincide).
// Position packet (UDP port 8308), 512-byte payload: timestamp at 198, PPS status at 202, NMEA
// $GPRMC sentence from byte 206.
//
// Example:
//   const auto layout = velodyne::packet_layout(sensor::SensorModel::VLP16);
//   const std::uint16_t azimuth = velodyne::read_u16(payload + velodyne::block_offset(3) + 2);

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "sensor/laser_calibration.hpp"

namespace conicloc::io::velodyne {

inline constexpr std::size_t kDataPacketBytes = 1206;
inline constexpr std::size_t kPositionPacketBytes = 512;
inline constexpr int kBlocksPerPacket = 12;
inline constexpr std::size_t kBlockBytes = 100;
inline constexpr int kRecordsPerBlock = 32;
inline constexpr std::size_t kRecordBytes = 3;
inline constexpr std::uint8_t kBlockFlag0 = 0xFF;
inline constexpr std::uint8_t kBlockFlag1 = 0xEE;
inline constexpr std::size_t kTimestampOffset = 1200;
inline constexpr std::size_t kReturnModeOffset = 1204;
inline constexpr std::size_t kProductIdOffset = 1205;
inline constexpr std::uint16_t kDataPort = 2368;
inline constexpr std::uint16_t kPositionPort = 8308;
inline constexpr double kDistanceUnitM = 0.002;
inline constexpr int kAzimuthUnitsPerTurn = 36000;  ///< hundredths of a degree
inline constexpr std::uint32_t kMicrosecondsPerHour = 3'600'000'000u;
inline constexpr int kMaxChannels = 32;

enum class ReturnMode : std::uint8_t { Strongest = 0x37, Last = 0x38, Dual = 0x39 };

/// Factory byte 1205. Old VLP-16 firmware writes 0x21 (HDL-32E): never trust it alone.
enum class ProductId : std::uint8_t {
  HDL32E = 0x21,
  VLP16 = 0x22,
  PuckHiRes = 0x24,
  VLP32C = 0x28
};

/// Which return a decoded point is. Dual mode labels both members of a pair; an identical pair
/// (one echo only) is emitted once as DualBoth.
enum class ReturnLabel : std::uint8_t { Strongest, Last, DualLast, DualStrongest, DualBoth };

/// How a model packs firings into blocks, and when each laser fires (manual timing tables).
struct PacketLayout {
  int channels = 16;                        ///< lasers per firing sequence
  int sequences_per_block = 2;              ///< firing sequences stored per block
  double channel_spacing_us = 2.304;        ///< time between consecutive channel firings
  int channels_per_slot = 1;                ///< lasers fired together (VLP-32C fires pairs)
  double sequence_period_us = 55.296;       ///< time between consecutive firing sequences
  double distance_unit_m = kDistanceUnitM;  ///< 2 mm; 4 mm on VLP-32C

  /// Time of channel `channel` of sequence `sequence` after the sequence 0 of its block.
  double firing_offset_us(int sequence, int channel) const {
    return sequence * sequence_period_us + (channel / channels_per_slot) * channel_spacing_us;
  }
  double block_period_us() const { return sequences_per_block * sequence_period_us; }
};

PacketLayout packet_layout(sensor::SensorModel model);

/// The product byte a model writes (Puck LITE shares the VLP-16's 0x22).
ProductId product_id(sensor::SensorModel model);

/// The model a product byte names, if known. Only a hint (see ProductId).
std::optional<sensor::SensorModel> model_from_product_id(std::uint8_t byte);

/// "strongest", "last", "dual" or "unknown(0x..)".
std::string return_mode_name(std::uint8_t byte);

/// "strongest", "last", "dual_last", "dual_strongest", "dual_both" (the CSV `return` column).
const char* return_label_name(ReturnLabel label);

inline std::size_t block_offset(int block) {
  return static_cast<std::size_t>(block) * kBlockBytes;
}

inline std::uint16_t read_u16(const std::uint8_t* p) {
  return static_cast<std::uint16_t>(p[0] | (p[1] << 8));
}
inline std::uint32_t read_u32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
         (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}
inline void write_u16(std::uint8_t* p, std::uint16_t v) {
  p[0] = static_cast<std::uint8_t>(v & 0xFF);
  p[1] = static_cast<std::uint8_t>(v >> 8);
}
inline void write_u32(std::uint8_t* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>((v >> (8 * i)) & 0xFF);
}

}  // namespace conicloc::io::velodyne
