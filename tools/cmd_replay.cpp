// `conicloc replay CAPTURE --to HOST:PORT [--speed X] [--loop]`: sends a capture's Velodyne packets
// over UDP at their recorded pace, as the sensor would (for `localize --udp`, tests and demos).
#include <spdlog/spdlog.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <thread>
#include <vector>

#include "io/open_capture.hpp"
#include "io/udp_sender.hpp"
#include "io/velodyne_packet.hpp"
#include "tools/commands.hpp"

namespace conicloc::tools {
namespace {

struct ReplayOptions {
  std::string capture;
  std::string topic;
  std::string to;  ///< "HOST:PORT" of the data packets
  int position_port = io::velodyne::kPositionPort;
  double speed = 1.0;
  bool loop = false;
};

struct ReplayCounts {
  std::size_t data = 0, position = 0, refused = 0;
};

std::atomic<bool> g_stop_replay{false};
extern "C" void stop_replay(int) {
  g_stop_replay.store(true);
}

// A data packet's device time stamp moved on by `shift_us` (µs past the hour, wrapping at the
// hour as the sensor's does): each pass of a loop continues the clock of the one before, so a
// receiver sees one sensor running on rather than time running backwards.
void shift_stamp(std::vector<std::uint8_t>& payload, std::uint64_t shift_us) {
  std::uint8_t* stamp = payload.data() + io::velodyne::kTimestampOffset;
  const std::uint64_t moved = io::velodyne::read_u32(stamp) + shift_us;
  io::velodyne::write_u32(stamp,
                          static_cast<std::uint32_t>(moved % io::velodyne::kMicrosecondsPerHour));
}

/// One pass over the capture, paced from `start` (capture time `pass_start_s` + offset is sent at
/// start + (t − first_time_s) / speed). Returns the capture time span of the pass plus one mean
/// packet interval (the next pass starts where this one would have gone on), 0 when it was empty.
double replay_pass(const ReplayOptions& o, io::UdpSender& data, io::UdpSender* position,
                   std::chrono::steady_clock::time_point start, std::uint64_t shift_us,
                   ReplayCounts& counts) {
  const auto capture = io::open_capture(
      o.capture,
      {.ports = {io::velodyne::kDataPort, io::velodyne::kPositionPort}, .topic = o.topic});
  std::optional<double> first_s;
  double last_s = 0.0;
  std::size_t sent = 0;
  std::vector<std::uint8_t> shifted;
  while (const auto datagram = capture->next()) {
    if (g_stop_replay.load()) break;
    if (!first_s) first_s = datagram->capture_time_s;
    last_s = datagram->capture_time_s;
    if (o.speed > 0) {
      const std::chrono::duration<double> offset((last_s - *first_s) / o.speed);
      std::this_thread::sleep_until(start +
                                    std::chrono::duration_cast<std::chrono::nanoseconds>(offset));
    }
    ++sent;
    if (datagram->dst_port == io::velodyne::kPositionPort) {
      if (!position) continue;
      counts.refused += position->send(datagram->payload) ? 0 : 1;
      ++counts.position;
      continue;
    }
    std::span<const std::uint8_t> payload = datagram->payload;
    if (shift_us > 0 && payload.size() == io::velodyne::kDataPacketBytes) {
      shifted.assign(payload.begin(), payload.end());
      shift_stamp(shifted, shift_us);
      payload = shifted;
    }
    counts.refused += data.send(payload) ? 0 : 1;
    ++counts.data;
  }
  if (!first_s || sent < 2) return 0.0;
  return (last_s - *first_s) * static_cast<double>(sent) / static_cast<double>(sent - 1);
}

void run_replay(const ReplayOptions& o) {
  io::UdpSender data(io::parse_send_endpoint(o.to, "--to"));
  std::unique_ptr<io::UdpSender> position;
  if (o.position_port > 0) {
    const auto to = io::parse_send_endpoint(o.to, "--to");
    position = std::make_unique<io::UdpSender>(
        io::UdpEndpoint{to.host, static_cast<std::uint16_t>(o.position_port)});
  }
  spdlog::info("replaying {} to {}{} at {}{}", o.capture, data.name(),
               position ? fmt::format(" (position packets to port {})", o.position_port) : "",
               o.speed > 0 ? fmt::format("{}x the recorded pace", o.speed) : "full speed",
               o.loop ? ", looping (Ctrl-C to stop)" : "");
  g_stop_replay.store(false);
  std::signal(SIGINT, stop_replay);

  ReplayCounts counts;
  std::size_t passes = 0;
  double shift_s = 0.0;  // capture time sent so far: where the next pass's clock starts
  const auto start = std::chrono::steady_clock::now();
  do {
    const auto pass_start =
        start + std::chrono::duration_cast<std::chrono::nanoseconds>(
                    std::chrono::duration<double>(o.speed > 0 ? shift_s / o.speed : 0.0));
    const double span_s =
        replay_pass(o, data, position.get(), pass_start,
                    static_cast<std::uint64_t>(std::llround(shift_s * 1e6)), counts);
    ++passes;
    if (span_s <= 0.0) break;  // an empty capture: nothing to loop over
    shift_s += span_s;
  } while (o.loop && !g_stop_replay.load());
  std::signal(SIGINT, SIG_DFL);

  const double elapsed_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  spdlog::info("sent {} data packets and {} position packets in {} pass{} ({:.2f} s)", counts.data,
               counts.position, passes, passes == 1 ? "" : "es", elapsed_s);
  if (counts.refused > 0) {
    spdlog::warn("{} datagrams refused by the system (nobody listening at {}?)", counts.refused,
                 data.name());
  }
}

}  // namespace

void add_replay_command(CLI::App& app) {
  auto o = std::make_shared<ReplayOptions>();
  auto* cmd = app.add_subcommand(
      "replay", "Send a capture's Velodyne packets over UDP at their recorded pace, as the sensor");
  cmd->add_option("capture", o->capture,
                  "pcap/pcapng file or ROS bag of velodyne_msgs/VelodyneScan (MCAP, .db3, .bag)")
      ->required()
      ->check(CLI::ExistingPath);
  cmd->add_option("--to", o->to, "HOST:PORT to send the data packets to (a sensor: port 2368)")
      ->required();
  cmd->add_option("--position-port", o->position_port,
                  "Send the capture's position packets to this port of HOST (0: do not send)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  cmd->add_option("--speed", o->speed,
                  "Pace: 1 as recorded, 2 twice as fast, 0 as fast as possible")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_flag("--loop", o->loop, "Start again at the end (device clock running on) until Ctrl-C");
  cmd->add_option("--topic", o->topic,
                  "Bag topic of velodyne_msgs/VelodyneScan (default: the only one)");
  cmd->callback([o] { run_replay(*o); });
}

}  // namespace conicloc::tools
