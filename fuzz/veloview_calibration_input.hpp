#pragma once
// Fuzz driver: VeloView XML calibrations (io::read_veloview_calibration, `--calibration`), then a
// decoder built from the accepted table decoding one fixed packet. Shared by
// fuzz/fuzz_veloview_calibration.cpp and test/test_fuzz_regressions.cpp.
//
// The input is the whole file; the model is VLP-16 for even sizes, HDL-32E for odd ones (16 and
// 32 lasers). io::InputError is the documented rejection; anything else is a finding, and so is
// an accepted table that decodes to non-finite points.

#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "fuzz/contract.hpp"
#include "fuzz/memory_file.hpp"
#include "io/input_error.hpp"
#include "io/velodyne_decoder.hpp"
#include "io/veloview_calibration.hpp"

namespace conicloc::fuzz {
namespace veloview_calibration_detail {

// A valid strongest-return packet: 12 blocks 0.2° apart, every range 10 m.
inline std::vector<std::uint8_t> fixed_packet() {
  namespace velodyne = io::velodyne;
  std::vector<std::uint8_t> packet(velodyne::kDataPacketBytes, 0);
  for (int b = 0; b < velodyne::kBlocksPerPacket; ++b) {
    std::uint8_t* block = packet.data() + velodyne::block_offset(b);
    block[0] = velodyne::kBlockFlag0;
    block[1] = velodyne::kBlockFlag1;
    velodyne::write_u16(block + 2, static_cast<std::uint16_t>(100 + 20 * b));
    for (int r = 0; r < velodyne::kRecordsPerBlock; ++r) {
      velodyne::write_u16(block + 4 + r * velodyne::kRecordBytes, 5000);
    }
  }
  packet[velodyne::kReturnModeOffset] = static_cast<std::uint8_t>(velodyne::ReturnMode::Strongest);
  return packet;
}

}  // namespace veloview_calibration_detail

inline void run_veloview_calibration(std::span<const std::uint8_t> input) {
  const MemoryFile file(input.data(), input.size());
  const auto model =
      input.size() % 2 == 0 ? sensor::SensorModel::VLP16 : sensor::SensorModel::HDL32E;
  try {
    const io::LoadedCalibration loaded = io::read_veloview_calibration(file.path(), model);
    require(loaded.calibration.model == model, "calibration of another model returned");
    const io::VelodyneDecoder decoder(loaded.calibration);
    static const auto packet = veloview_calibration_detail::fixed_packet();
    require(decoder.check(packet) == io::PacketCheck::Ok, "the fixed packet was refused");
    std::vector<io::DecodedPoint> points;
    decoder.decode(packet, 0.0, points);
    for (const auto& point : points) {
      require(std::isfinite(point.x_m) && std::isfinite(point.y_m) && std::isfinite(point.z_m),
              "an accepted calibration decodes to non-finite points");
    }
  } catch (const io::InputError&) {
    // The documented rejection: malformed XML, a missing or non-numeric field, a bad laser id.
  }
}

}  // namespace conicloc::fuzz
