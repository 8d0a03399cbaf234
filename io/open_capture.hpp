#pragma once
// Opens a capture of Velodyne packets by its content, not its name: pcap and pcapng (PcapReader),
// MCAP, ROS 1 bags (version 2.0) and ROS 2 .db3 bags (BagCaptureSource over the bag's reader). A
// ROS 2 bag folder (metadata.yaml beside one .db3 or .mcap file) opens that file. A bag of point
// clouds holds no packets: open it as scans (io/scan_source.hpp).
//
// Example:
//   auto capture = io::open_capture("run.bag", {.topic = "/velodyne_packets"});
//   io::VelodyneStream stream(*capture, calibration);

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/bag_reader.hpp"
#include "io/capture_source.hpp"
#include "io/velodyne_packet.hpp"

namespace conicloc::io {

struct CaptureOptions {
  /// pcap: the UDP destination ports to deliver (empty: all). Bags hold data packets only, which
  /// are delivered as sent to the first port.
  std::vector<std::uint16_t> ports = {velodyne::kDataPort, velodyne::kPositionPort};
  /// Bags: the topic of velodyne_msgs/VelodyneScan or sensor_msgs/PointCloud2 messages ("": the
  /// only one there is).
  std::string topic;
};

/// The format `path` holds by its first bytes: "pcap", "pcapng", "MCAP", "ROS 1 bag",
/// "ROS 2 db3", or "" when it is none of them (or cannot be read).
std::string sniff_capture_format(const std::string& path);

/// A bag with its topic chosen (io/bag_topic.hpp).
struct OpenedBag {
  std::string file;    ///< the bag file (a folder's storage file)
  std::string format;  ///< as sniff_capture_format
  std::unique_ptr<BagReader> reader;
  BagTopic topic;
};

/// Opens `path` as a bag and chooses its topic; nullopt when it is not a bag. Throws InputError
/// (place "topics") when no topic is usable, listing them.
std::optional<OpenedBag> open_bag(const std::string& path, const std::string& topic);

/// Opens `path`. Throws InputError when it cannot be read, is not a capture, or (bags) has no
/// usable topic, or it holds point clouds); anything unrecognised is given to libpcap, whose
/// message then says why not.
std::unique_ptr<CaptureSource> open_capture(const std::string& path,
                                            const CaptureOptions& options = {});

}  // namespace conicloc::io
