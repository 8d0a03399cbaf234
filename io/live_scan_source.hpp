#pragma once
// Scans from a live sensor: a receiving thread reads the UDP packets (UdpReceiver), assembles
// whole rotations exactly as a capture's packets are assembled (PacketScanSource) and hands them
// to the filter through a DropQueue. The receiving thread never waits for the filter: when the
// filter falls behind, the oldest whole scan waiting is dropped and counted, never a part of one.
// Device time is put on UTC by the first data packet's arrival time, as a capture's is by its
// capture time, so a capture replayed live gives the scans (and times, up to one constant) of
// the capture read from file.
//
// Example:
//   io::LiveScanSource live(calibration, {.receiver = {.listen = {"", 2368}}});
//   while (auto scan = live.next()) localizer.update(*scan);   // ends after the idle timeout
//   spdlog::info("{} scans dropped", live.dropped_scans());

#include <exception>
#include <mutex>
#include <thread>

#include "io/drop_queue.hpp"
#include "io/packet_scan_source.hpp"
#include "io/udp_receiver.hpp"

namespace conicloc::io {

struct LiveSourceConfig {
  UdpReceiverConfig receiver;
  std::size_t queue_depth = 2;  ///< whole scans waiting for the filter, at most
  StreamConfig stream;          ///< its ports are set to the ones bound
  ScanAssemblerConfig assembler;
};

class LiveScanSource final : public ScanSource {
 public:
  /// Binds the sockets (throws InputError as UdpReceiver) and starts receiving.
  LiveScanSource(const sensor::LaserCalibration& calibration, const LiveSourceConfig& config);
  ~LiveScanSource() override;
  LiveScanSource(const LiveScanSource&) = delete;
  LiveScanSource& operator=(const LiveScanSource&) = delete;

  /// Waits for the next whole scan; nullopt once the receiver stopped (idle timeout or stop())
  /// and every queued scan was taken. Rethrows what ended the receiving thread, if anything did.
  std::optional<sensor::Scan> next() override;
  /// Of the scan next() returned last, as its source saw them when the scan was complete.
  std::optional<double> utc_offset_s() const override { return utc_offset_s_; }
  double rotation_rpm() const override { return rotation_rpm_; }
  /// counts() and stream() are complete once next() returned nullopt; read them only then.
  const CaptureCounts& counts() const override { return packets_.counts(); }
  std::string format() const override { return packets_.format(); }
  std::string name() const override { return name_; }
  const VelodyneStream* stream() const override { return packets_.stream(); }

  /// Ends reception within ~0.2 s. Safe to call from a signal handler.
  void stop() { receiver_->stop(); }
  std::uint16_t port() const { return receiver_->port(); }
  std::optional<std::uint16_t> position_port() const { return receiver_->position_port(); }
  /// Whole scans assembled so far, and how many of them the filter never got.
  std::size_t assembled_scans() const { return queue_.pushed(); }
  std::size_t dropped_scans() const { return queue_.dropped(); }
  /// Rejected data packets named since the last call (the stream names the first
  /// VelodyneStream::kNamedRejections of a run), for logging them while the run goes on.
  std::vector<RejectedPacket> take_rejections();

 private:
  struct QueuedScan {
    sensor::Scan scan;
    std::optional<double> utc_offset_s;
    double rotation_rpm = 0.0;
  };

  LiveScanSource(const sensor::LaserCalibration& calibration, const LiveSourceConfig& config,
                 std::unique_ptr<UdpReceiver> receiver);
  static std::unique_ptr<UdpReceiver> open_receiver(const LiveSourceConfig& config);
  static ScanSourceOptions packet_options(const LiveSourceConfig& config,
                                          const UdpReceiver& receiver);
  void receive();
  void forward_rejections();

  UdpReceiver* receiver_;  ///< owned by packets_
  std::string name_;
  PacketScanSource packets_;
  DropQueue<QueuedScan> queue_;
  std::optional<double> utc_offset_s_;
  double rotation_rpm_ = 0.0;
  std::mutex rejections_mutex_;
  std::vector<RejectedPacket> new_rejections_;
  std::size_t forwarded_rejections_ = 0;  ///< receiving thread only
  std::exception_ptr error_;              ///< written by the thread before it closes the queue
  std::thread thread_;                    ///< last: starts once everything above exists
};

}  // namespace conicloc::io
