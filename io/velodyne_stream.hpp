#pragma once
// A Velodyne packet stream: reads datagrams from a capture or socket, sorts data (port 2368) from
// position (port 8308) packets, rejects bad packets by reason, unwraps the device clock (µs past
// the hour → monotonic seconds) and decodes the good ones. Nothing is thrown for bad packets:
// they are counted in stats() and every good packet before and after is decoded.
//
// Example:
//   io::PcapReader reader("run.pcap", {2368, 8308});
//   io::VelodyneStream stream(reader, sensor::builtin_calibration(sensor::SensorModel::VLP16));
//   std::vector<io::DecodedPoint> points;
//   while (stream.next(points)) assembler.add(points, scans);
//   for (const auto& w : stream.warnings()) spdlog::warn("{}", w);

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "io/datagram_source.hpp"
#include "io/velodyne_decoder.hpp"
#include "io/velodyne_position.hpp"

namespace conicloc::io {

struct StreamConfig {
  std::uint16_t data_port = velodyne::kDataPort;
  std::uint16_t position_port = velodyne::kPositionPort;
  /// The sensor's IPv4 address, host byte order (0: any sender). Two sensors sending to one port
  /// are told apart by it; packets of other senders are counted, not decoded. A datagram whose
  /// sender is unknown (a bag's) is not this sensor's.
  std::uint32_t source_address = 0;
  int max_block_step_cdeg = 200;          ///< see VelodyneDecoder
  std::size_t timing_check_packets = 64;  ///< packets used to check the model against timing
};

struct StreamStats {
  std::size_t datagrams = 0;     ///< every datagram of the sensor seen on the two ports
  std::size_t other_senders = 0;  ///< datagrams on the two ports from another address
  std::size_t data_packets = 0;  ///< decoded
  std::size_t position_packets = 0;
  std::size_t points = 0;                                 ///< decoded records, no-returns included
  std::array<std::size_t, kPacketCheckCount> rejected{};  ///< by PacketCheck
  std::size_t bad_position_packets = 0;                   ///< wrong size on the position port
  std::size_t packets_lost = 0;             ///< estimated from time gaps between good packets
  std::size_t clock_wraps = 0;              ///< hourly wraps of the device clock
  std::optional<std::uint8_t> return_mode;  ///< factory byte of the first good packet
  std::optional<std::uint8_t> product_id;
  std::optional<PositionPacket> last_position;
  std::optional<double> utc_hour_start_s;  ///< from the first dated GPRMC
  double first_time_s = 0.0;               ///< device time (unwrapped) of the first good packet
  double last_time_s = 0.0;
  double turned_cdeg = 0.0;    ///< azimuth covered between consecutive good packets
  double turned_time_s = 0.0;  ///< time over which turned_cdeg was measured

  std::size_t rejected_total() const;
  /// Mean rotation rate, revolutions per minute; 0 when unknown.
  double rotation_rpm() const;
};

/// A data packet that was not decoded: where it was (DatagramSource record), who sent it (live
/// sources) and why.
struct RejectedPacket {
  std::size_t record = 0;
  PacketCheck check = PacketCheck::Ok;
  std::size_t bytes = 0;
  std::uint32_t src_address = 0;  ///< IPv4, host byte order; 0 where unknown
  std::uint16_t src_port = 0;
};

class VelodyneStream {
 public:
  VelodyneStream(DatagramSource& source, const sensor::LaserCalibration& calibration,
                 StreamConfig config = {});

  /// Decodes the next good data packet into `points` (cleared first). False at the end of input.
  bool next(std::vector<DecodedPoint>& points);

  const StreamStats& stats() const { return stats_; }
  /// Model / product-byte / timing mismatches found so far (each once).
  const std::vector<std::string>& warnings() const { return warnings_; }
  /// The first kNamedRejections rejected data packets, in order (stats() counts all of them).
  const std::vector<RejectedPacket>& first_rejections() const { return rejections_; }
  static constexpr std::size_t kNamedRejections = 100;
  const VelodyneDecoder& decoder() const { return decoder_; }

 private:
  void handle_position(const UdpDatagram& datagram);
  void check_timing(double period_us);
  void reject(const UdpDatagram& datagram, PacketCheck check);

  DatagramSource& source_;
  VelodyneDecoder decoder_;
  StreamConfig config_;
  StreamStats stats_;
  std::vector<std::string> warnings_;
  std::vector<RejectedPacket> rejections_;
  bool have_previous_ = false;
  std::uint32_t previous_stamp_ = 0;
  int previous_first_azimuth_ = 0;
  double hours_s_ = 0.0;
  std::vector<double> periods_us_;
  bool timing_checked_ = false;
};

}  // namespace conicloc::io
