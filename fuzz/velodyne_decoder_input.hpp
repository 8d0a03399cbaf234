#pragma once
// Fuzz driver: Velodyne data and position packet decoding (io/velodyne_decoder,
// io/velodyne_position) and scan assembly of the decoded points. Shared by
// fuzz/fuzz_velodyne_decoder.cpp and the corpus replay in test/test_fuzz_regressions.cpp.
//
// Input: byte 0 selects the sensor model (bits 0-2) and whether to force the 12 block flags
// (bit 3) and the return-mode byte (bit 4, mode from bits 5-6) so the mutator spends its time past
// check(); the rest is the payload, decoded as a data packet (any size: check() must refuse wrong
// sizes) and as a position packet (padded / cut to 512 bytes, and the raw bytes as an NMEA line).
// None of these functions throws on bad bytes: any exception is a finding.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "fuzz/contract.hpp"
#include "io/scan_assembler.hpp"
#include "io/velodyne_decoder.hpp"
#include "io/velodyne_position.hpp"
#include "sensor/builtin_calibration.hpp"

namespace conicloc::fuzz {
namespace velodyne_decoder_detail {

constexpr std::array kModels = {sensor::SensorModel::VLP16, sensor::SensorModel::PuckLite,
                                sensor::SensorModel::PuckHiRes, sensor::SensorModel::HDL32E,
                                sensor::SensorModel::VLP32C};

inline const io::VelodyneDecoder& decoder_for(std::size_t model_index) {
  // Decoders build trig tables: one per model for the whole run.
  static const std::array<io::VelodyneDecoder, kModels.size()> decoders = {
      io::VelodyneDecoder(sensor::builtin_calibration(kModels[0])),
      io::VelodyneDecoder(sensor::builtin_calibration(kModels[1])),
      io::VelodyneDecoder(sensor::builtin_calibration(kModels[2])),
      io::VelodyneDecoder(sensor::builtin_calibration(kModels[3])),
      io::VelodyneDecoder(sensor::builtin_calibration(kModels[4]))};
  return decoders[model_index];
}

inline void run_position(std::span<const std::uint8_t> bytes) {
  std::vector<std::uint8_t> packet(io::velodyne::kPositionPacketBytes, 0);
  std::copy_n(bytes.begin(), std::min(bytes.size(), packet.size()), packet.begin());
  if (const auto position = io::parse_position_packet(packet)) {
    if (const auto hour_start_s = io::utc_hour_start(*position)) {
      require(std::isfinite(*hour_start_s), "utc_hour_start is not finite");
    }
    (void)io::pps_status_name(position->pps_status);
  } else {
    require(false, "a 512-byte position packet was refused");
  }
  require(!io::parse_position_packet(bytes) || bytes.size() == io::velodyne::kPositionPacketBytes,
          "parse_position_packet accepted a payload that is not 512 bytes");
  (void)io::parse_gprmc(std::string(bytes.begin(), bytes.end()));
}

}  // namespace velodyne_decoder_detail

inline void run_velodyne_decoder(std::span<const std::uint8_t> input) {
  using namespace velodyne_decoder_detail;
  namespace velodyne = io::velodyne;
  if (input.empty()) return;
  const std::uint8_t control = input[0];
  std::vector<std::uint8_t> payload(input.begin() + 1, input.end());
  run_position(payload);

  if ((control & 0x08) && payload.size() == velodyne::kDataPacketBytes) {
    for (int b = 0; b < velodyne::kBlocksPerPacket; ++b) {
      payload[velodyne::block_offset(b)] = velodyne::kBlockFlag0;
      payload[velodyne::block_offset(b) + 1] = velodyne::kBlockFlag1;
    }
  }
  if ((control & 0x10) && payload.size() == velodyne::kDataPacketBytes) {
    payload[velodyne::kReturnModeOffset] = static_cast<std::uint8_t>(0x37 + (control >> 5) % 3);
  }
  const io::VelodyneDecoder& decoder = decoder_for((control & 0x07) % kModels.size());
  const io::PacketCheck check = decoder.check(payload);
  (void)io::packet_check_name(check);
  if (check != io::PacketCheck::Ok) return;

  std::vector<io::DecodedPoint> points;
  const double packet_time_s = io::VelodyneDecoder::timestamp_us(payload) * 1e-6;
  const std::size_t count = decoder.decode(payload, packet_time_s, points);
  require(count == points.size(), "decode() count differs from the points appended");
  for (const auto& point : points) {
    // Documented ranges (velodyne_decoder.hpp): θ in [0, 2π), a channel of the model.
    require(point.azimuth_rad >= 0.0f && point.azimuth_rad < static_cast<float>(2.0 * M_PI),
            "decoded azimuth outside [0, 2π)");
    require(point.channel < decoder.layout().channels, "decoded channel beyond the model's");
    require(point.firing_azimuth_cdeg < velodyne::kAzimuthUnitsPerTurn,
            "firing azimuth beyond 360°");
    require(std::isfinite(point.x_m) && std::isfinite(point.y_m) && std::isfinite(point.z_m),
            "decoded point not finite");
  }
  io::ScanAssembler assembler(decoder.calibration());
  std::vector<sensor::Scan> scans;
  assembler.add(points, scans);
  (void)assembler.finish();
}

}  // namespace conicloc::fuzz
