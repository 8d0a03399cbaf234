#pragma once
// Where a capture went wrong, for the log: a cut-short or broken record, the first skipped bag
// chunks and messages, and the first rejected data packets, each by record number (and byte
// offset where the format gives one).

#include <arpa/inet.h>
#include <spdlog/spdlog.h>

#include <string>
#include <vector>

#include "io/capture_source.hpp"
#include "io/udp_endpoint.hpp"
#include "io/velodyne_stream.hpp"

namespace conicloc::tools {

/// "CAPTURE: record 17: data packet rejected (why)"; a live datagram also names its sender and
/// size: "udp://:2368: datagram 17 from 10.0.0.5:2368 (13 bytes): data packet rejected (why)".
inline void log_rejected_packet(const std::string& capture, const io::RejectedPacket& rejected,
                                bool live) {
  if (!live || rejected.src_address == 0) {
    spdlog::warn("{}: record {}: data packet rejected ({})", capture, rejected.record,
                 io::packet_check_name(rejected.check));
    return;
  }
  sockaddr_in sender{};
  sender.sin_addr.s_addr = htonl(rejected.src_address);
  sender.sin_port = htons(rejected.src_port);
  spdlog::warn("{}: datagram {} from {} ({} bytes): data packet rejected ({})", capture,
               rejected.record, io::address_text(sender), rejected.bytes,
               io::packet_check_name(rejected.check));
}

inline void log_capture_problems(const std::string& capture, const io::CaptureCounts* counts,
                                 const io::StreamStats& stats,
                                 const std::vector<io::RejectedPacket>& first_rejections) {
  if (counts && counts->bag && counts->truncated_records) {
    spdlog::warn(
        "{}: {}: cut short or broken; reading stopped after {} messages of the topic ({})", capture,
        counts->stop_offset ? fmt::format("byte offset {}", *counts->stop_offset)
                            : std::string("message " + std::to_string(counts->records + 1)),
        counts->records, counts->stop_message);
  } else if (counts && counts->truncated_records) {
    spdlog::warn(
        "{}: record {}{}: cut short or broken; reading stopped after {} complete records ({})",
        capture, counts->records + 1,
        counts->stop_offset ? fmt::format(" at byte offset {}", *counts->stop_offset) : "",
        counts->records, counts->stop_message);
  }
  if (counts) {
    for (const auto& problem : counts->problems) spdlog::warn("{}: {}", capture, problem);
    const std::size_t skipped = counts->bad_chunks + counts->bad_messages;
    if (skipped > counts->problems.size()) {
      spdlog::warn("{}: {} more skipped chunks or messages not listed", capture,
                   skipped - counts->problems.size());
    }
  }
  for (const auto& rejected : first_rejections) log_rejected_packet(capture, rejected, false);
  if (stats.rejected_total() > first_rejections.size()) {
    spdlog::warn("{}: {} more rejected data packets not listed", capture,
                 stats.rejected_total() - first_rejections.size());
  }
}

}  // namespace conicloc::tools
