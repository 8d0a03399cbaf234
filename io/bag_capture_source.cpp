#include "io/bag_capture_source.hpp"

namespace conicloc::io {

BagCaptureSource::BagCaptureSource(std::string path, std::string format,
                                   std::unique_ptr<BagReader> reader, BagTopic topic,
                                   std::uint16_t data_port)
    : path_(std::move(path)),
      format_(std::move(format)),
      reader_(std::move(reader)),
      topic_(std::move(topic)),
      data_port_(data_port) {}

std::optional<UdpDatagram> BagCaptureSource::next() {
  while (next_packet_ >= scan_.packets.size()) {
    const auto message = reader_->next();
    if (!message) return std::nullopt;
    scan_.packets.clear();
    next_packet_ = 0;
    try {
      scan_ = decode_velodyne_scan(message->data, *topic_.encoding);
    } catch (const MessageError& e) {
      auto& counts = reader_->counts();
      ++counts.bad_messages;
      if (counts.problems.size() < CaptureCounts::kNamedProblems) {
        counts.problems.push_back(message->place + ": " + e.what() + "; skipped");
      }
    }
  }
  const VelodynePacketView& packet = scan_.packets[next_packet_++];
  UdpDatagram datagram;
  datagram.payload = packet.data;
  datagram.capture_time_s = packet.stamp_s;
  datagram.src_port = data_port_;
  datagram.dst_port = data_port_;
  datagram.record = ++packets_;
  ++reader_->counts().udp_datagrams;
  return datagram;
}

}  // namespace conicloc::io
