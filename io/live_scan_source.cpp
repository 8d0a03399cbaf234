#include "io/live_scan_source.hpp"

#include <utility>

namespace conicloc::io {

std::unique_ptr<UdpReceiver> LiveScanSource::open_receiver(const LiveSourceConfig& config) {
  return std::make_unique<UdpReceiver>(config.receiver);
}

ScanSourceOptions LiveScanSource::packet_options(const LiveSourceConfig& config,
                                                 const UdpReceiver& receiver) {
  ScanSourceOptions options;
  options.stream = config.stream;
  options.stream.data_port = receiver.port();
  // No datagram arrives for port 0: without a position socket nothing is taken for position.
  options.stream.position_port = receiver.position_port().value_or(0);
  options.assembler = config.assembler;
  return options;
}

LiveScanSource::LiveScanSource(const sensor::LaserCalibration& calibration,
                               const LiveSourceConfig& config)
    : LiveScanSource(calibration, config, open_receiver(config)) {}

LiveScanSource::LiveScanSource(const sensor::LaserCalibration& calibration,
                               const LiveSourceConfig& config,
                               std::unique_ptr<UdpReceiver> receiver)
    : receiver_(receiver.get()),
      name_(receiver->name()),
      packets_(std::move(receiver), calibration, packet_options(config, *receiver_)),
      queue_(config.queue_depth),
      thread_([this] { receive(); }) {}

LiveScanSource::~LiveScanSource() {
  stop();
  if (thread_.joinable()) thread_.join();
}

void LiveScanSource::receive() {
  try {
    while (auto scan = packets_.next()) {
      forward_rejections();
      queue_.push({std::move(*scan), packets_.utc_offset_s(), packets_.rotation_rpm()});
    }
    forward_rejections();
  } catch (...) {
    error_ = std::current_exception();
  }
  queue_.close();
}

void LiveScanSource::forward_rejections() {
  const auto& named = packets_.stream()->first_rejections();
  if (forwarded_rejections_ == named.size()) return;
  const std::lock_guard lock(rejections_mutex_);
  new_rejections_.insert(new_rejections_.end(),
                         named.begin() + static_cast<std::ptrdiff_t>(forwarded_rejections_),
                         named.end());
  forwarded_rejections_ = named.size();
}

std::vector<RejectedPacket> LiveScanSource::take_rejections() {
  const std::lock_guard lock(rejections_mutex_);
  return std::exchange(new_rejections_, {});
}

std::optional<sensor::Scan> LiveScanSource::next() {
  auto queued = queue_.pop();
  if (!queued) {
    if (thread_.joinable()) thread_.join();
    if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
    return std::nullopt;
  }
  utc_offset_s_ = queued->utc_offset_s;
  rotation_rpm_ = queued->rotation_rpm;
  return std::move(queued->scan);
}

}  // namespace conicloc::io
