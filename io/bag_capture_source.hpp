#pragma once
// The Velodyne packets of a bag's VelodyneScan topic (chosen by open_bag()): decodes each
// VelodyneScan message and hands out its packets one by one as datagrams on the data port, stamped
// with the packet's own stamp. A message that does not decode is counted, named (first few) and
// skipped.

#include <memory>
#include <string>

#include "io/bag_reader.hpp"
#include "io/capture_source.hpp"

namespace conicloc::io {

class BagCaptureSource : public CaptureSource {
 public:
  /// `reader`: selected on `topic`, a VelodyneScan topic.
  BagCaptureSource(std::string path, std::string format, std::unique_ptr<BagReader> reader,
                   BagTopic topic, std::uint16_t data_port);

  std::optional<UdpDatagram> next() override;
  std::string name() const override { return path_; }
  const CaptureCounts& counts() const override { return reader_->counts(); }
  std::string format() const override { return format_; }
  const BagTopic& topic() const { return topic_; }

 private:
  std::string path_;
  std::string format_;
  std::unique_ptr<BagReader> reader_;
  BagTopic topic_;
  std::uint16_t data_port_;
  VelodyneScanView scan_;
  std::size_t next_packet_ = 0;
  std::size_t packets_ = 0;
};

}  // namespace conicloc::io
