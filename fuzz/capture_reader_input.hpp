#pragma once
// Fuzz driver: a capture file (pcap or pcapng through libpcap, or a ROS bag: MCAP, ROS 1 bag,
// ROS 2 .db3; opened by io::open_capture by its content) driven to its end through
// io::VelodyneStream and io::ScanAssembler, as `conicloc localize` reads one.
// Shared by fuzz/fuzz_capture_reader.cpp and test/test_fuzz_regressions.cpp.
//
// The input is the whole file. The model is guessed from the capture first (as the tools do), so
// guess_model_from_capture() is fuzzed too. io::InputError is the documented rejection of a file
// that is not a capture (or has an unsupported link type); any other exception is a finding.

#include <cstdint>
#include <cstring>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "fuzz/contract.hpp"
#include "fuzz/memory_file.hpp"
#include "fuzz/temp_file.hpp"
#include "io/input_error.hpp"
#include "io/open_capture.hpp"
#include "io/pcap_reader.hpp"
#include "io/scan_assembler.hpp"
#include "io/velodyne_model_guess.hpp"
#include "io/velodyne_stream.hpp"
#include "sensor/builtin_calibration.hpp"

namespace conicloc::fuzz {
namespace capture_reader_detail {

// Building a VelodyneStream builds its decoder's trig tables (~100 000 cos/sin), which would be
// 90 % of the time per input. One never-used prototype stream per model is built once, reading
// through this forwarding source; each input gets a fresh copy (same tables, fresh state) with
// the forwarder pointed at that input's reader.
class ForwardingSource : public io::DatagramSource {
 public:
  std::optional<io::UdpDatagram> next() override { return target->next(); }
  std::string name() const override { return target->name(); }
  io::DatagramSource* target = nullptr;
};

inline ForwardingSource& forwarding_source() {
  static ForwardingSource source;
  return source;
}

inline const io::VelodyneStream& prototype_stream(sensor::SensorModel model) {
  static std::map<sensor::SensorModel, io::VelodyneStream> prototypes;
  auto it = prototypes.find(model);
  if (it == prototypes.end()) {
    it = prototypes
             .emplace(model,
                      io::VelodyneStream(forwarding_source(), sensor::builtin_calibration(model)))
             .first;
  }
  return it->second;
}

}  // namespace capture_reader_detail

inline void run_capture_reader(std::span<const std::uint8_t> input) {
  namespace velodyne = io::velodyne;
  // SQLite cannot open a memfd (fuzz/temp_file.hpp): a .db3 goes to disk, the rest stays in memory.
  const bool sqlite = input.size() >= 16 && std::memcmp(input.data(), "SQLite format 3", 16) == 0;
  std::optional<MemoryFile> memory;
  std::optional<TempFile> disk;
  if (sqlite) {
    disk.emplace(input.data(), input.size());
  } else {
    memory.emplace(input.data(), input.size());
  }
  const std::string path = sqlite ? disk->path() : memory->path();
  try {
    const auto guess = io::guess_model_from_capture(path, velodyne::kDataPort, 32);
    const auto model = guess ? guess->model : sensor::SensorModel::VLP16;
    const auto calibration = sensor::builtin_calibration(model);

    const auto capture = io::open_capture(path);
    capture_reader_detail::forwarding_source().target = capture.get();
    io::VelodyneStream stream = capture_reader_detail::prototype_stream(model);
    io::ScanAssembler assembler(calibration);
    std::vector<io::DecodedPoint> points;
    std::vector<sensor::Scan> scans;
    while (stream.next(points)) {
      assembler.add(points, scans);
      scans.clear();  // keep memory flat on long inputs, as the localizer does
    }
    (void)assembler.finish();
    const io::StreamStats& stats = stream.stats();
    // Both ports were asked for: every delivered datagram reached the stream, and each one was
    // decoded, rejected by reason, or is a position packet (good or bad).
    require(stats.datagrams == capture->counts().udp_datagrams,
            "datagrams lost between reader and stream");
    require(stats.data_packets + stats.rejected_total() + stats.position_packets +
                    stats.bad_position_packets ==
                stats.datagrams,
            "a datagram is neither decoded, rejected nor a position packet");
    require(stats.last_time_s >= stats.first_time_s, "stream time went backwards");
    (void)stats.rotation_rpm();
    if (const auto* pcap = dynamic_cast<const io::PcapReader*>(capture.get())) {
      (void)pcap->link_type_name();
    }
  } catch (const io::InputError&) {
    // The documented rejection: not a capture, an unsupported link type, a bag without a usable
    // topic or with an unknown chunk compression.
  }
}

}  // namespace conicloc::fuzz
