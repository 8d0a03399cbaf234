// `conicloc localize --udp` on loopback, fed by `conicloc replay` of a short simulated capture:
// the same poses as `localize --pcap` of that capture; a throttled filter drops whole scans and
// says so; garbage datagrams are named and change no pose; a sender that stops (or Ctrl-C) ends
// the run cleanly with its summary; `--pose-udp` sends a JSON line per pose.
//
// Tolerance: none on poses. Replayed live, the filter gets the same scans (same packets, same
// assembly) with the same seed, so it writes the same digits; times differ by one constant (the
// host clock at arrival instead of the capture clock), equal up to the 1 µs print rounding of
// each (2 µs for a difference of two).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "io/live_scan_source.hpp"
#include "io/packet_encoder.hpp"
#include "io/pcap_writer.hpp"
#include "io/tum_trajectory.hpp"
#include "io/udp_receiver.hpp"
#include "io/udp_sender.hpp"
#include "sensor/builtin_calibration.hpp"
#include "test/background_run.hpp"
#include "test/cli_guarded_run.hpp"
#include "test/cli_run.hpp"
#include "test/temp_path.hpp"

namespace fs = std::filesystem;
using conicloc::test::BackgroundRun;
using conicloc::test::GuardedRun;

namespace {

constexpr double kTimeTolerance_s = 2e-6;

struct TumLine {
  double time_s = 0.0;
  std::string pose;  ///< the seven pose fields as printed
};

std::vector<TumLine> tum_lines(const std::string& text) {
  std::vector<TumLine> lines;
  std::stringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    const auto space = line.find(' ');
    lines.push_back({std::stod(line.substr(0, space)), line.substr(space + 1)});
  }
  return lines;
}

std::size_t number_after(const std::string& text, const std::string& pattern) {
  std::smatch match;
  if (!std::regex_search(text, match, std::regex(pattern))) return SIZE_MAX;
  return std::stoul(match[1]);
}

class LocalizeLive : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = conicloc::test::unique_temp_path("localize_live");
    fs::create_directories(dir_);
    capture_ = (dir_ / "run.pcap").string();
    const auto simulated =
        conicloc::test::run_guarded(dir_, "simulate --duration 2 --seed 4 --out '" + capture_ +
                                              "' --truth '" + (dir_ / "truth.tum").string() + "'");
    if (simulated.exit_code != 0) return;
    const auto truth = conicloc::io::read_tum((dir_ / "truth.tum").string());
    filter_ = {"--init",           conicloc::test::init_argument(truth.front().pose),
               "--init-sigma",     "0.05,0.05,1",
               "--seed",           "3",
               "--init-particles", "300",
               "--min-particles",  "200",
               "--threads",        "1"};
    std::string flags;
    for (const auto& word : filter_) flags += " " + word;
    offline_ =
        conicloc::test::run_guarded(dir_, "localize --pcap '" + capture_ + "' --out -" + flags);
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  void SetUp() override {
    ASSERT_EQ(offline_.exit_code, 0) << offline_.err;
    offline_poses_ = tum_lines(offline_.out);
    ASSERT_GT(offline_poses_.size(), 10u);
  }

  /// Starts `localize --udp 127.0.0.1:0` with `extra` flags; its port once it listens.
  std::uint16_t start_live(std::unique_ptr<BackgroundRun>& live,
                           const std::vector<std::string>& extra) {
    std::vector<std::string> arguments = {"localize", "--udp", "127.0.0.1:0", "--position-port",
                                          "0"};
    arguments.insert(arguments.end(), filter_.begin(), filter_.end());
    arguments.insert(arguments.end(), extra.begin(), extra.end());
    live = std::make_unique<BackgroundRun>(dir_, arguments);
    EXPECT_TRUE(live->started());
    const auto port = live->wait_for_log(R"(listening on udp://127\.0\.0\.1:(\d+))", 60);
    EXPECT_TRUE(port.has_value()) << live->err();
    return port ? static_cast<std::uint16_t>(std::stoi(*port)) : 0;
  }

  GuardedRun replay(std::uint16_t port, const std::string& speed) {
    return conicloc::test::run_guarded(dir_, "replay '" + capture_ +
                                                 "' --to 127.0.0.1:" + std::to_string(port) +
                                                 " --speed " + speed + " --position-port 0");
  }

  /// The live poses are the offline ones: same digits, times shifted by one constant.
  void expect_offline_poses(const std::vector<TumLine>& live) const {
    ASSERT_EQ(live.size(), offline_poses_.size());
    const double shift_s = live.front().time_s - offline_poses_.front().time_s;
    for (std::size_t k = 0; k < live.size(); ++k) {
      EXPECT_EQ(live[k].pose, offline_poses_[k].pose) << "pose " << k;
      EXPECT_NEAR(live[k].time_s - offline_poses_[k].time_s, shift_s, kTimeTolerance_s) << k;
    }
  }

  /// "N whole scans received: P localized, D dropped ..., S partial skipped".
  static std::size_t received(const std::string& log) {
    return number_after(log, R"((\d+) whole scans received)");
  }
  static std::size_t dropped(const std::string& log) {
    return number_after(log, R"((\d+) dropped while the filter was busy)");
  }
  static std::size_t skipped_live(const std::string& log) {
    return number_after(log, R"((\d+) partial skipped)");
  }
  static std::size_t skipped_offline() {
    return number_after(offline_.err, R"(\((\d+) partial scans empty)");
  }

  static inline fs::path dir_;
  static inline std::string capture_;
  static inline std::vector<std::string> filter_;
  static inline GuardedRun offline_;
  std::vector<TumLine> offline_poses_;
};

TEST_F(LocalizeLive, ReplayedCaptureGivesTheOfflinePosesOnStdout) {
  std::unique_ptr<BackgroundRun> live;
  // Deep enough for every scan of the capture: nothing can be dropped, whatever the load.
  const auto port = start_live(live, {"--idle-timeout", "1", "--queue-depth", "100", "--out", "-"});
  ASSERT_NE(port, 0);
  const auto sent = replay(port, "4");
  ASSERT_EQ(sent.exit_code, 0) << sent.err;
  EXPECT_NE(sent.err.find("position packets in 1 pass"), std::string::npos) << sent.err;
  const auto run = live->wait(120);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  expect_offline_poses(tum_lines(run.out));
  EXPECT_EQ(dropped(run.err), 0u) << run.err;
  EXPECT_EQ(received(run.err), offline_poses_.size() + skipped_offline()) << run.err;
}

TEST_F(LocalizeLive, AThrottledFilterDropsWholeScansAndSaysSo) {
  std::unique_ptr<BackgroundRun> live;
  const auto out = dir_ / "throttled.tum";
  const auto port = start_live(live, {"--idle-timeout", "1", "--queue-depth", "1", "--throttle-ms",
                                      "500", "--out", out.string()});
  ASSERT_NE(port, 0);
  ASSERT_EQ(replay(port, "1").exit_code, 0);
  const auto run = live->wait(120);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto poses = tum_lines(conicloc::test::slurp(out));
  ASSERT_FALSE(poses.empty());
  EXPECT_GT(dropped(run.err), 0u) << run.err;
  // Every scan sent was assembled whole, then localized, dropped or (cut short) skipped.
  EXPECT_EQ(received(run.err), offline_poses_.size() + skipped_offline()) << run.err;
  EXPECT_EQ(poses.size() + dropped(run.err) + skipped_live(run.err), received(run.err)) << run.err;
  // Each pose is for one whole scan of the capture: its time is one of the offline scan times
  // (up to the clock shift, found from the first pose).
  bool matched = false;
  for (const auto& first : offline_poses_) {
    const double shift_s = poses.front().time_s - first.time_s;
    std::size_t found = 0;
    for (const auto& pose : poses) {
      for (const auto& offline : offline_poses_) {
        if (std::abs(pose.time_s - offline.time_s - shift_s) < kTimeTolerance_s) ++found;
      }
    }
    matched = matched || found == poses.size();
  }
  EXPECT_TRUE(matched);
}

TEST_F(LocalizeLive, GarbageDatagramsAreNamedAndChangeNoPose) {
  std::unique_ptr<BackgroundRun> live;
  const auto out = dir_ / "garbage.tum";
  const auto port =
      start_live(live, {"--idle-timeout", "1", "--queue-depth", "100", "--out", out.string()});
  ASSERT_NE(port, 0);
  {
    conicloc::io::UdpSender garbage({"127.0.0.1", port});
    garbage.send(std::string("not a packet"));
    garbage.send(std::string(1206, '\xee'));  // the right size, no block flags
    garbage.send(std::string(512, 'x'));      // a position packet's size
  }
  ASSERT_EQ(replay(port, "4").exit_code, 0);
  const auto run = live->wait(120);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string name = "udp://127.0.0.1:" + std::to_string(port);
  for (const char* datagram :
       {"datagram 1 from 127.0.0.1:", "datagram 2 from 127.0.0.1:", "datagram 3 from 127.0.0.1:"}) {
    EXPECT_NE(run.err.find(name + ": " + datagram), std::string::npos) << datagram << run.err;
  }
  EXPECT_NE(run.err.find("(12 bytes): data packet rejected"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("3 bad datagrams"), std::string::npos) << run.err;
  expect_offline_poses(tum_lines(conicloc::test::slurp(out)));
}

TEST_F(LocalizeLive, ASenderThatStopsEndsTheRunAfterTheIdleTimeout) {
  std::unique_ptr<BackgroundRun> live;
  const auto port =
      start_live(live, {"--idle-timeout", "1", "--out", (dir_ / "stops.tum").string()});
  ASSERT_NE(port, 0);
  ASSERT_EQ(replay(port, "4").exit_code, 0);
  const auto stopped = std::chrono::steady_clock::now();
  // 1 s of silence, then at most the two queued scans: the limit only tells an end from a hang.
  const auto run = live->wait(30);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const double waited_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - stopped).count();
  EXPECT_GE(waited_s, 0.8);  // it did wait for the sender (poll steps of 0.2 s)
  EXPECT_NE(received(run.err), SIZE_MAX) << run.err;
  EXPECT_NE(run.err.find("bad datagrams"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("scans localized"), std::string::npos) << run.err;
}

TEST_F(LocalizeLive, CtrlCEndsTheRunWithItsSummary) {
  std::unique_ptr<BackgroundRun> live;
  const auto port =
      start_live(live, {"--idle-timeout", "0", "--out", (dir_ / "interrupted.tum").string()});
  ASSERT_NE(port, 0);
  ASSERT_EQ(replay(port, "4").exit_code, 0);
  ::kill(live->pid(), SIGINT);
  const auto run = live->wait(30);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_GT(received(run.err), 0u) << run.err;
  EXPECT_NE(received(run.err), SIZE_MAX) << run.err;
  EXPECT_NE(run.err.find("scans localized"), std::string::npos) << run.err;
}

TEST_F(LocalizeLive, PoseUdpSendsOneJsonLinePerPose) {
  conicloc::io::UdpReceiver consumer(0, 0.5);
  std::unique_ptr<BackgroundRun> live;
  const auto out = dir_ / "sent.tum";
  const auto port =
      start_live(live, {"--idle-timeout", "1", "--queue-depth", "100", "--out", out.string(),
                        "--pose-udp", "127.0.0.1:" + std::to_string(consumer.port())});
  ASSERT_NE(port, 0);
  ASSERT_EQ(replay(port, "4").exit_code, 0);
  ASSERT_EQ(live->wait(120).exit_code, 0);
  const auto poses = tum_lines(conicloc::test::slurp(out));
  std::size_t k = 0;
  const std::regex line(
      R"re(^\{"time":([-+0-9.e]+),"pose":\{"x":([-+0-9.e]+),"y":[-+0-9.e]+,"z":[-+0-9.e]+,)re"
      R"re("qx":[-+0-9.e]+,"qy":[-+0-9.e]+,"qz":[-+0-9.e]+,"qw":[-+0-9.e]+\},)re"
      R"re("covariance":\[((?:[-+0-9.e]+,){35}[-+0-9.e]+)\],"status":"([a-z]+)"\}\n$)re");
  while (const auto datagram = consumer.next()) {
    const std::string text(datagram->payload.begin(), datagram->payload.end());
    std::smatch match;
    ASSERT_TRUE(std::regex_match(text, match, line)) << text;
    ASSERT_LT(k, poses.size());
    EXPECT_NEAR(std::stod(match[1]), poses[k].time_s, 1e-6);
    EXPECT_NEAR(std::stod(match[2]), std::stod(poses[k].pose), 1e-6);  // x, printed to 1 µm
    EXPECT_NE(match[4], "");
    ++k;
  }
  EXPECT_EQ(k, poses.size());
}

}  // namespace

namespace {

// 400 VLP-16 packets at 600 rpm (0.53 s), written as a capture.
std::string short_capture(const fs::path& dir) {
  conicloc::io::PacketEncoder encoder;
  for (int i = 0; i < 400 * 24; ++i) {
    conicloc::io::FiringSequence s;
    s.time_s = 100.0 + i * 55.296e-6;
    s.azimuth_rad = 2.0 - 2 * M_PI * 10.0 * i * 55.296e-6;
    for (int k = 0; k < 16; ++k) s.range_m[k] = 3.0 + 0.1 * k;
    encoder.add(s);
  }
  const std::string path = (dir / "short.pcap").string();
  conicloc::io::PcapWriter writer(path);
  for (const auto& p : encoder.take_packets()) writer.write_udp(p.payload, 1.7e9 + p.time_s);
  return path;
}

TEST(ReplayCommand, LoopRunsTheDeviceClockOnUntilCtrlC) {
  const auto dir = conicloc::test::unique_temp_path("replay_loop");
  fs::create_directories(dir);
  const std::string capture = short_capture(dir);
  conicloc::io::LiveSourceConfig config;
  config.receiver.listen = {"127.0.0.1", 0};
  // Silence counts from the receiver's start, and the replay is another process: under the
  // sanitizers on a loaded machine it once took over 0.6 s to send its first packet, and the
  // receiver had ended (0 packets of 90,096 sent). The timeout also ends the run after Ctrl-C.
  config.receiver.idle_timeout_s = 3.0;
  config.queue_depth = 1000;
  conicloc::io::LiveScanSource live(
      conicloc::sensor::builtin_calibration(conicloc::sensor::SensorModel::VLP16), config);
  BackgroundRun replay(dir, {"replay", capture, "--to", "127.0.0.1:" + std::to_string(live.port()),
                             "--speed", "4", "--loop", "--position-port", "0"});
  ASSERT_TRUE(replay.started());
  // Three passes: 18 scans.
  for (int waited_ms = 0; live.assembled_scans() < 18 && waited_ms < 30000; waited_ms += 10) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ::kill(replay.pid(), SIGINT);
  const auto run = replay.wait(30);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::size_t passes = number_after(run.err, R"(in (\d+) passes)");
  EXPECT_GE(passes, 3u) << run.err;
  std::size_t scans = 0;
  while (live.next()) ++scans;
  const auto& stats = live.stream()->stats();
  // Each pass continued the clock of the one before: no time ran backwards, no packet seemed
  // lost at the seams, and the scans between the seams were whole.
  EXPECT_EQ(stats.rejected_total(), 0u);
  EXPECT_EQ(stats.packets_lost, 0u);
  EXPECT_GE(stats.data_packets, 3 * 400u - 400u);
  EXPECT_EQ(stats.data_packets, number_after(run.err, R"(sent (\d+) data packets)"));
  EXPECT_GE(scans, 18u);
  fs::remove_all(dir);
}

TEST(LocalizeLiveFlags, BadEndpointsAndInputsAreNamed) {
  const auto dir = conicloc::test::unique_temp_path("live_flags");
  fs::create_directories(dir);
  auto run = conicloc::test::run_guarded(dir, "localize --udp 127.0.0.1:99999 --out -");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("--udp: '127.0.0.1:99999'"), std::string::npos) << run.err;
  run = conicloc::test::run_guarded(
      dir, "localize --udp 127.0.0.1:0 --idle-timeout 1 --pose-udp 9000 --out -");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("--pose-udp: '9000': expected HOST:PORT"), std::string::npos) << run.err;
  run = conicloc::test::run_guarded(dir, "localize --out -");
  EXPECT_TRUE(run.clean_exit());
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.err.find("--pcap or --udp"), std::string::npos) << run.err;
  const auto text = dir / "notes.txt";
  std::ofstream(text) << "not a capture\n";
  run = conicloc::test::run_guarded(dir, "replay '" + text.string() + "' --to 127.0.0.1:9");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find(text.string()), std::string::npos) << run.err;
  run = conicloc::test::run_guarded(dir, "replay '" + text.string() + "' --to 127.0.0.1");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("--to: '127.0.0.1': expected HOST:PORT"), std::string::npos) << run.err;
  fs::remove_all(dir);
}

}  // namespace
