#pragma once
// Scans from Velodyne packets: a capture's datagrams through VelodyneStream and ScanAssembler. The
// device clock is related to UTC by the first data packet's capture time (the packet leaves the
// sensor after its last firing).

#include <deque>

#include "io/scan_source.hpp"

namespace conicloc::io {

class PacketScanSource final : public ScanSource {
 public:
  PacketScanSource(std::unique_ptr<CaptureSource> capture,
                   const sensor::LaserCalibration& calibration, const ScanSourceOptions& options);

  std::optional<sensor::Scan> next() override;
  std::optional<double> utc_offset_s() const override { return utc_offset_s_; }
  double rotation_rpm() const override { return stream_.stats().rotation_rpm(); }
  const CaptureCounts& counts() const override { return capture_->counts(); }
  std::string format() const override { return capture_->format(); }
  std::string name() const override { return capture_->name(); }
  const VelodyneStream* stream() const override { return &stream_; }

 private:
  // Passes the capture's datagrams through and remembers the capture time of the last one.
  class TimedSource final : public DatagramSource {
   public:
    explicit TimedSource(CaptureSource& inner) : inner_(inner) {}
    std::optional<UdpDatagram> next() override {
      auto datagram = inner_.next();
      if (datagram) last_capture_time_s = datagram->capture_time_s;
      return datagram;
    }
    std::string name() const override { return inner_.name(); }
    double last_capture_time_s = 0.0;

   private:
    CaptureSource& inner_;
  };

  std::unique_ptr<CaptureSource> capture_;
  TimedSource timed_;
  VelodyneStream stream_;
  ScanAssembler assembler_;
  std::optional<double> utc_offset_s_;
  std::deque<sensor::Scan> ready_;
  std::vector<DecodedPoint> points_;
  bool ended_ = false;
};

}  // namespace conicloc::io
