#pragma once
// Opens a capture of Velodyne packets by its content, not its name: pcap and pcapng (PcapReader),
// MCAP, ROS 1 bags (version 2.0) and ROS 2 .db3 bags (BagCaptureSource over the bag's reader). A
// ROS 2 bag folder (metadata.yaml beside one .db3 or .mcap file) opens that file.
//
// Example:
//   auto capture = io::open_capture("run.bag", {.topic = "/velodyne_packets"});
//   io::VelodyneStream stream(*capture, calibration);

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "io/capture_source.hpp"
#include "io/velodyne_packet.hpp"

namespace conicloc::io {

struct CaptureOptions {
  /// pcap: the UDP destination ports to deliver (empty: all). Bags hold data packets only, which
  /// are delivered as sent to the first port.
  std::vector<std::uint16_t> ports = {velodyne::kDataPort, velodyne::kPositionPort};
  /// Bags: the topic of velodyne_msgs/VelodyneScan messages ("": the only one there is).
  std::string topic;
};

/// The format `path` holds by its first bytes: "pcap", "pcapng", "MCAP", "ROS 1 bag",
/// "ROS 2 db3", or "" when it is none of them (or cannot be read).
std::string sniff_capture_format(const std::string& path);

/// Opens `path`. Throws InputError when it cannot be read, is not a capture, or (bags) has no
/// usable topic; anything unrecognised is given to libpcap, whose message then says why not.
std::unique_ptr<CaptureSource> open_capture(const std::string& path,
                                            const CaptureOptions& options = {});

}  // namespace conicloc::io
