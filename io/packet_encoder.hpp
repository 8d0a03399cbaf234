#pragma once
// Encodes firing sequences into Velodyne data packets (the inverse of the decoder; the simulator
// writes its captures with it).
//
// A firing sequence is every laser fired once at one azimuth: 16 channels on VLP-16 / Pucks, 32 on
// HDL-32E / VLP-32C. Give the sequences in firing order, one every `layout.sequence_period_us`
// (55.296 µs on VLP-16) — the packet stores only the time of its first firing, the decoder derives
// the others from that period. Azimuths are REP-103 (counter-clockwise from x, radians); inside
// they become Velodyne's clockwise hundredths of a degree, α = −θ. A block stores the azimuth of
// its first sequence; the decoder interpolates the second, so the sensor should turn uniformly.
// Ranges are rounded to 2 mm (4 mm on VLP-32C); 0, negative, non-finite or beyond 65534 units
// (131.07 m at 2 mm) is written as "no return".
//
// Example (VLP-16, strongest return, 10 Hz):
//   io::PacketEncoder encoder({.model = sensor::SensorModel::VLP16});
//   io::PcapWriter pcap("run.pcap");
//   for (int i = 0; i < n; ++i) {
//     io::FiringSequence s;
//     s.time_s = t0 + i * 55.296e-6;
//     s.azimuth_rad = -2 * M_PI * 10.0 * i * 55.296e-6;   // the sensor spins clockwise seen from
//     above for (int k = 0; k < 16; ++k) { s.range_m[k] = ranges[i][k]; s.intensity[k] = 40; }
//     encoder.add(s);
//     for (const auto& packet : encoder.take_packets()) pcap.write_udp(packet.payload, utc0 +
//     packet.time_s);
//   }
//   encoder.flush();   // pads and emits the last partial packet
//   for (const auto& packet : encoder.take_packets()) pcap.write_udp(packet.payload, utc0 +
//   packet.time_s);
//
// Dual return mode: set `return_mode = Dual` and fill `second_range_m` / `second_intensity` with
// the strongest echo (range_m / intensity hold the last echo). A sequence with second_range_m = 0
// is written as the sensor does with a single echo: both blocks identical.

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "io/velodyne_packet.hpp"
#include "sensor/laser_calibration.hpp"

namespace conicloc::io {

struct EncoderConfig {
  sensor::SensorModel model = sensor::SensorModel::VLP16;
  velodyne::ReturnMode return_mode = velodyne::ReturnMode::Strongest;
  std::optional<std::uint8_t> product_id =
      std::nullopt;  ///< factory byte 1205; default: the model's own
};

/// One firing sequence (see the file comment). Channels beyond the model's count are ignored.
struct FiringSequence {
  double azimuth_rad = 0.0;  ///< θ of the sequence's first firing, REP-103, any value (wrapped)
  double time_s = 0.0;       ///< device time of the first firing; stored modulo one hour
  std::array<double, velodyne::kMaxChannels> range_m{};  ///< per channel; 0 = no return
  std::array<std::uint8_t, velodyne::kMaxChannels> intensity{};
  std::array<double, velodyne::kMaxChannels> second_range_m{};  ///< dual mode: strongest echo
  std::array<std::uint8_t, velodyne::kMaxChannels> second_intensity{};
};

struct EncodedPacket {
  std::array<std::uint8_t, velodyne::kDataPacketBytes> payload{};
  double time_s = 0.0;  ///< device time of the packet's first firing (the caller's clock)
};

class PacketEncoder {
 public:
  explicit PacketEncoder(EncoderConfig config = {});

  /// Appends one sequence; a completed packet is queued for take_packets().
  void add(const FiringSequence& sequence);

  /// Pads a partly filled packet with no-return sequences (azimuth and time continued at the last
  /// step) and queues it. Does nothing when no sequence is pending.
  void flush();

  /// The completed packets since the last call, in order.
  std::vector<EncodedPacket> take_packets();

  /// Firing sequences per packet: 24 (VLP-16 strongest/last), 12 (dual, or 32-laser models), 6.
  int sequences_per_packet() const;

  const velodyne::PacketLayout& layout() const { return layout_; }

 private:
  void write_sequence(const FiringSequence& sequence, int slot);

  EncoderConfig config_;
  velodyne::PacketLayout layout_;
  EncodedPacket current_;
  int pending_ = 0;  ///< sequences written into current_
  std::optional<FiringSequence> last_;
  double last_step_rad_ = 0.0;
  std::vector<EncodedPacket> done_;
};

/// Velodyne azimuth (clockwise hundredths of a degree, 0..35999) of a REP-103 angle θ.
std::uint16_t velodyne_azimuth_from_rad(double azimuth_rad);

/// Microseconds past the hour of a device time in seconds.
std::uint32_t microseconds_past_hour(double time_s);

}  // namespace conicloc::io
