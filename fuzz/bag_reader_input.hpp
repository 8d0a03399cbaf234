#pragma once
// Fuzz drivers: one bag reader (io::McapReader, io::Rosbag1Reader, io::Ros2Db3Reader) on its own,
// and the VelodyneScan message decoder. Shared by fuzz/fuzz_{mcap,rosbag1,ros2_db3}_reader.cpp,
// fuzz/fuzz_velodyne_scan_msg.cpp and test/test_fuzz_regressions.cpp.
//
// A bag: its topics are listed, the first VelodyneScan topic (else the first topic) is selected
// and read to its end, and every message of a readable encoding is decoded. io::InputError (not a
// bag, an unknown chunk compression) and io::MessageError (a message that is not a VelodyneScan)
// are the documented rejections; anything else, or a broken guarantee, is a finding.

#include <cstdint>
#include <span>
#include <string>

#include "fuzz/contract.hpp"
#include "fuzz/memory_file.hpp"
#include "fuzz/temp_file.hpp"
#include "io/bag_reader.hpp"
#include "io/input_error.hpp"
#include "io/velodyne_scan_msg.hpp"

namespace conicloc::fuzz {

/// Decodes `message`; checks that every packet view lies inside it and is a whole packet.
inline void check_velodyne_scan(std::span<const std::uint8_t> message,
                                io::MessageEncoding encoding) {
  try {
    const io::VelodyneScanView scan = io::decode_velodyne_scan(message, encoding);
    for (const auto& packet : scan.packets) {
      require(packet.data.size() == io::kVelodynePacketBytes, "a packet view of the wrong size");
      require(packet.data.data() >= message.data() &&
                  packet.data.data() + packet.data.size() <= message.data() + message.size(),
              "a packet view outside the message");
    }
  } catch (const io::MessageError&) {
    // The documented rejection of a cut or malformed message.
  }
}

/// The message decoder: the first byte picks the encoding (even ROS 1, odd CDR), the rest is the
/// message.
inline void run_velodyne_scan_msg(std::span<const std::uint8_t> input) {
  if (input.empty()) return;
  const auto encoding = input[0] % 2 == 0 ? io::MessageEncoding::Ros1 : io::MessageEncoding::Cdr;
  check_velodyne_scan(input.subspan(1), encoding);
}

/// The number of messages read (0 for a rejected input). `File` holds the input as a file:
/// MemoryFile, or TempFile for SQLite.
template <class Reader, class File = MemoryFile>
std::size_t run_bag_reader(std::span<const std::uint8_t> input) {
  const File file(input.data(), input.size());
  try {
    Reader reader(file.path());
    const auto topics = reader.topics();
    const io::BagTopic* chosen = topics.empty() ? nullptr : &topics.front();
    for (const auto& topic : topics) {
      if (io::is_velodyne_scan_type(topic.type)) {
        chosen = &topic;
        break;
      }
    }
    if (chosen == nullptr) return 0;
    reader.select(chosen->name);
    std::size_t messages = 0;
    while (const auto message = reader.next()) {
      ++messages;
      require(!message->place.empty(), "a message without its place in the file");
      if (chosen->encoding) check_velodyne_scan(message->data, *chosen->encoding);
    }
    require(!reader.next().has_value(), "a message after the end");
    const io::CaptureCounts& counts = reader.counts();
    require(counts.truncated_records <= 1, "more than one place where the file broke");
    require(counts.truncated_records == 0 || !counts.stop_message.empty(),
            "reading stopped without saying why");
    require(counts.problems.size() <= io::CaptureCounts::kNamedProblems, "too many named problems");
    return messages;
  } catch (const io::InputError&) {
    // The documented rejection: not a bag of this format, an unknown chunk compression.
  }
  return 0;
}

}  // namespace conicloc::fuzz
