// End to end: simulate in the two-room box building, write the pcap, read and decode it with io/,
// place the points with the true poses and compare with the map.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/pcap_reader.hpp"
#include "io/pcap_writer.hpp"
#include "io/velodyne_decoder.hpp"
#include "localizer/conic/pose.hpp"
#include "sensor/builtin_calibration.hpp"
#include "sim/box_building.hpp"
#include "sim/simulation.hpp"
#include "test/temp_path.hpp"

namespace conicloc::sim {
namespace {

std::string temp_path(const std::string& name) {
  return conicloc::test::unique_temp_path("sim_" + name).string();
}

SimulationConfig clean_config(double duration_s) {
  SimulationConfig config;
  config.duration_s = duration_s;
  config.disable_effects();
  return config;
}

struct Recording {
  SimulationStats stats;
  std::vector<std::vector<std::uint8_t>> payloads;
  std::vector<double> utc_s;
};

Recording record(Simulation& simulation) {
  Recording r;
  r.stats = simulation.run([&](const io::EncodedPacket& packet, double utc) {
    r.payloads.emplace_back(packet.payload.begin(), packet.payload.end());
    r.utc_s.push_back(utc);
  });
  return r;
}

std::string write_pcap(const Recording& recording, const std::string& name) {
  const std::string path = temp_path(name);
  io::PcapWriter writer(path);
  for (std::size_t i = 0; i < recording.payloads.size(); ++i) {
    writer.write_udp(recording.payloads[i], recording.utc_s[i]);
  }
  writer.close();
  return path;
}

// Distance of a map point to the nearest polygon plane whose box (grown 0.25 m) holds it.
double plane_distance(const std::vector<maps::PlanarPolygon>& polygons, const Eigen::Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& polygon : polygons) {
    Eigen::AlignedBox3d box = polygon.bounds;
    box.min().array() -= 0.25;
    box.max().array() += 0.25;
    if (box.contains(p)) best = std::min(best, std::abs(polygon.plane.signed_distance(p)));
  }
  return best;
}

struct Residuals {
  std::size_t valid = 0;
  std::size_t records = 0;
  double rms_on_plane_m = 0.0;  ///< over points within 0.2 m of a plane
  std::size_t off_plane = 0;    ///< farther than 0.2 m from every map plane
};

Residuals decode_and_compare(const std::string& pcap, const Simulation& simulation,
                             const maps::PlaneMap& map) {
  io::PcapReader reader(pcap, {2368});
  io::VelodyneDecoder decoder(sensor::builtin_calibration(sensor::SensorModel::VLP16));
  std::vector<io::DecodedPoint> points;
  Residuals r;
  double sum_sq = 0.0;
  std::size_t on_plane = 0;
  while (auto datagram = reader.next()) {
    EXPECT_EQ(decoder.check(datagram->payload), io::PacketCheck::Ok);
    points.clear();
    decoder.decode(datagram->payload, datagram->capture_time_s - simulation.config().start_epoch_s,
                   points);
    for (const auto& point : points) {
      ++r.records;
      if (point.range_m <= 0.0f) continue;
      ++r.valid;
      const Eigen::Vector3d p_map = simulation.trajectory().T_map_sensor(point.time_s) *
                                    Eigen::Vector3d(point.x_m, point.y_m, point.z_m);
      const double d = plane_distance(map.polygons, p_map);
      if (d > 0.2) {
        ++r.off_plane;
      } else {
        sum_sq += d * d;
        ++on_plane;
      }
    }
  }
  r.rms_on_plane_m = std::sqrt(sum_sq / std::max<std::size_t>(on_plane, 1));
  return r;
}

TEST(SimRecording, PacketRateIs754PerSecondAtEveryRpm) {
  const auto map = make_box_building();
  for (const double rpm : {300.0, 600.0, 1200.0}) {
    auto config = clean_config(1.0);
    config.sensor.rpm = rpm;
    Simulation simulation(map, config);
    const auto recording = record(simulation);
    // 1 s / (24 × 55.296 µs) = 753.5 packets.
    EXPECT_NEAR(static_cast<double>(recording.stats.packets), 754.0, 1.0) << rpm;
    // The head turns ω·55.296 µs per sequence: 0.199° at 600 rpm. Block 0 → block 1 is two steps.
    const auto& p = recording.payloads[10];
    const int a0 = io::velodyne::read_u16(p.data() + io::velodyne::block_offset(0) + 2);
    const int a1 = io::velodyne::read_u16(p.data() + io::velodyne::block_offset(1) + 2);
    const double expected_cdeg = rpm / 60.0 * 36000.0 * 2 * 55.296e-6;
    EXPECT_NEAR((a1 - a0 + 36000) % 36000, expected_cdeg, 1.01) << rpm;
  }
}

TEST(SimRecording, PointsLieOnTheMapWithTheConfiguredNoise) {
  const auto map = make_box_building();
  auto config = clean_config(1.5);
  config.effects.range_noise_m = 0.03;
  config.effects.quantisation_m = 0.002;
  Simulation simulation(map, config);
  const auto recording = record(simulation);
  const auto path = write_pcap(recording, "noise.pcap");
  const auto r = decode_and_compare(path, simulation, map);
  EXPECT_EQ(r.valid, recording.stats.sensor.map_hits);
  ASSERT_GT(r.valid, 100000u);
  // Range noise along the beam projects onto the plane normal by cos(incidence) ≤ 1, so the
  // point-to-plane RMS lies a little below σ; within 20 %.
  EXPECT_NEAR(r.rms_on_plane_m, 0.03, 0.2 * 0.03);
  EXPECT_LT(static_cast<double>(r.off_plane), 1e-3 * r.valid);
  std::remove(path.c_str());
}

TEST(SimRecording, ExactWithoutEffects) {
  const auto map = make_box_building();
  Simulation simulation(map, clean_config(0.3));
  const auto recording = record(simulation);
  const auto path = write_pcap(recording, "exact.pcap");
  const auto r = decode_and_compare(path, simulation, map);
  ASSERT_GT(r.valid, 10000u);
  // Only the packet's 2 mm range step and float points remain.
  EXPECT_LT(r.rms_on_plane_m, 0.0015);
  EXPECT_EQ(r.off_plane, 0u);
  std::remove(path.c_str());
}

TEST(SimRecording, DropoutsAtTheConfiguredRate) {
  const auto map = make_box_building();
  auto config = clean_config(1.0);
  config.effects.dropout_rate = 0.1;
  Simulation simulation(map, config);
  const auto s = record(simulation).stats.sensor;
  const double rate =
      static_cast<double>(s.dropouts) / static_cast<double>(s.dropouts + s.map_hits);
  EXPECT_NEAR(rate, 0.1, 0.005);
}

TEST(SimRecording, ClutterAppearsOffTheMapAtItsRate) {
  const auto map = make_box_building();
  auto config = clean_config(1.5);
  config.clutter.level = 3;
  config.seed = 5;
  Simulation simulation(map, config);
  const auto recording = record(simulation);
  ASSERT_GT(recording.stats.furniture_boxes, 0);
  const auto path = write_pcap(recording, "clutter.pcap");
  const auto r = decode_and_compare(path, simulation, map);
  const auto& s = recording.stats.sensor;
  const double clutter_rate =
      static_cast<double>(s.furniture_hits + s.person_hits) / static_cast<double>(r.valid);
  const double off_rate = static_cast<double>(r.off_plane) / static_cast<double>(r.valid);
  EXPECT_GT(clutter_rate, 0.01);
  // Clutter near a wall or the floor (box tops within 0.2 m, feet) counts as on a plane.
  EXPECT_LE(off_rate, clutter_rate + 1e-9);
  EXPECT_GT(off_rate, 0.5 * clutter_rate);
  std::remove(path.c_str());
}

TEST(SimRecording, SameSeedSameBytesAnyThreads) {
  const auto map = make_box_building();
  SimulationConfig config;  // every effect on
  config.duration_s = 0.5;
  config.clutter.level = 2;
  config.seed = 42;
  Simulation a(map, config);
  config.threads = 2;
  Simulation b(map, config);
  config.threads = 1;
  config.seed = 43;
  Simulation c(map, config);
  const auto ra = record(a);
  const auto rb = record(b);
  const auto rc = record(c);
  EXPECT_EQ(ra.payloads, rb.payloads);
  EXPECT_EQ(ra.utc_s, rb.utc_s);
  EXPECT_NE(ra.payloads, rc.payloads);
}

TEST(SimRecording, ANoiseSeedRedrawsTheNoiseAndNothingElse) {
  const auto map = make_box_building();
  SimulationConfig config;  // every effect on: map error, clutter, calibration errors, noise
  config.duration_s = 0.5;
  config.clutter.level = 2;
  config.effects.elevation_error_deg = 0.1;
  config.seed = 42;
  Simulation plain(map, config);
  config.noise_seed = 7;
  Simulation redrawn(map, config);
  Simulation again(map, config);
  const auto r_plain = record(plain);
  const auto r_redrawn = record(redrawn);
  EXPECT_EQ(r_redrawn.payloads, record(again).payloads);
  EXPECT_NE(r_redrawn.payloads, r_plain.payloads);
  EXPECT_EQ(r_redrawn.utc_s, r_plain.utc_s);
  // The same route, world and sensor errors.
  const auto truth_plain = plain.truth();
  const auto truth_redrawn = redrawn.truth();
  ASSERT_EQ(truth_redrawn.size(), truth_plain.size());
  for (std::size_t i = 0; i < truth_plain.size(); ++i)
    EXPECT_EQ(truth_redrawn[i].pose.matrix(), truth_plain[i].pose.matrix()) << "pose " << i;
  EXPECT_EQ(redrawn.sensor().elevation_errors_rad(), plain.sensor().elevation_errors_rad());
  ASSERT_EQ(redrawn.world().polygons().size(), plain.world().polygons().size());
  for (std::size_t i = 0; i < plain.world().polygons().size(); ++i) {
    EXPECT_EQ(redrawn.world().polygons()[i].plane.signed_distance(Eigen::Vector3d::Zero()),
              plain.world().polygons()[i].plane.signed_distance(Eigen::Vector3d::Zero()));
  }
  EXPECT_EQ(redrawn.world().people().size(), plain.world().people().size());
}

TEST(SimRecording, ASecondSensorSendsItsOwnPacketsAndChangesNoneOfTheFirst) {
  const auto map = make_box_building();
  SimulationConfig config;  // every effect on
  config.duration_s = 0.3;
  config.seed = 42;
  Simulation alone(map, config);
  const auto first_alone = record(alone);
  config.second_sensor = localizer::make_pose(0.1, -0.2, 0.3, 1.2, 0.05, -0.03);
  Simulation pair(map, config);
  Recording first, second;
  std::vector<double> order_utc;
  pair.run(
      [&](const io::EncodedPacket& packet, double utc) {
        first.payloads.emplace_back(packet.payload.begin(), packet.payload.end());
        order_utc.push_back(utc);
      },
      [&](const io::EncodedPacket& packet, double utc) {
        second.payloads.emplace_back(packet.payload.begin(), packet.payload.end());
        order_utc.push_back(utc);
      });
  EXPECT_EQ(first.payloads, first_alone.payloads);  // its own random streams
  EXPECT_EQ(second.payloads.size(), first.payloads.size());
  EXPECT_NE(second.payloads, first.payloads);
  EXPECT_TRUE(std::is_sorted(order_utc.begin(), order_utc.end()));  // one capture, in time order
  ASSERT_NE(pair.second_sensor(), nullptr);
  EXPECT_NE(pair.second_sensor()->true_calibration().lasers[0].elevation_rad,
            pair.sensor().true_calibration().lasers[0].elevation_rad);  // its own errors

  // Without effects, a second sensor where the first is measures what the first does (the
  // intensities' jitter is its own).
  auto clean = clean_config(0.2);
  clean.second_sensor = Eigen::Isometry3d::Identity();
  Simulation twin(map, clean);
  Recording a, b;
  twin.run(
      [&](const io::EncodedPacket& p, double) {
        a.payloads.emplace_back(p.payload.begin(), p.payload.end());
      },
      [&](const io::EncodedPacket& p, double) {
        b.payloads.emplace_back(p.payload.begin(), p.payload.end());
      });
  ASSERT_EQ(a.payloads.size(), b.payloads.size());
  io::VelodyneDecoder decoder(sensor::builtin_calibration(sensor::SensorModel::VLP16));
  std::vector<io::DecodedPoint> pa, pb;
  for (std::size_t i = 0; i < a.payloads.size(); ++i) {
    decoder.decode(a.payloads[i], 0.0, pa);
    decoder.decode(b.payloads[i], 0.0, pb);
    ASSERT_EQ(pa.size(), pb.size());
    for (std::size_t j = 0; j < pa.size(); ++j) {
      ASSERT_EQ(pa[j].range_m, pb[j].range_m) << "packet " << i << " point " << j;
      ASSERT_EQ(pa[j].azimuth_rad, pb[j].azimuth_rad);
    }
  }
}

TEST(SimRecording, DualReturnDoublesThePacketRate) {
  const auto map = make_box_building();
  auto config = clean_config(0.5);
  config.sensor.dual_return = true;
  Simulation simulation(map, config);
  const auto recording = record(simulation);
  EXPECT_NEAR(static_cast<double>(recording.stats.packets), 2 * 376.75, 1.5);
  EXPECT_EQ(recording.payloads[0][io::velodyne::kReturnModeOffset], 0x39);
  EXPECT_GT(recording.stats.sensor.second_echoes, 0u);  // at the door and room edges
}

TEST(SimRecording, HourRollOverInTheDeviceClock) {
  const auto map = make_box_building();
  auto config = clean_config(0.2);
  config.start_epoch_s = 1767229200.0 - 0.1;  // 0.1 s before 2026-01-01T01:00:00Z
  Simulation simulation(map, config);
  const auto recording = record(simulation);
  std::uint32_t first = io::VelodyneDecoder::timestamp_us(recording.payloads.front());
  std::uint32_t last = io::VelodyneDecoder::timestamp_us(recording.payloads.back());
  EXPECT_GT(first, 3'599'800'000u);
  EXPECT_LT(last, 200'000u);
  EXPECT_NEAR(recording.utc_s.front(), config.start_epoch_s, 1e-6);
}

TEST(SimRecording, TcpdumpReadsTheCaptureCleanly) {
  const char* tcpdump = std::filesystem::exists("/usr/sbin/tcpdump")  ? "/usr/sbin/tcpdump"
                        : std::filesystem::exists("/usr/bin/tcpdump") ? "/usr/bin/tcpdump"
                                                                      : nullptr;
  if (tcpdump == nullptr) GTEST_SKIP() << "tcpdump not installed";
  const auto map = make_box_building();
  Simulation simulation(map, clean_config(0.2));
  const auto recording = record(simulation);
  const auto path = write_pcap(recording, "tcpdump.pcap");
  const std::string out = temp_path("tcpdump.out");
  const std::string err = temp_path("tcpdump.err");
  const std::string command = std::string(tcpdump) + " -r " + path + " -nn > " + out + " 2> " + err;
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::ifstream lines(out);
  std::string line;
  std::size_t count = 0;
  while (std::getline(lines, line)) {
    ++count;
    EXPECT_NE(line.find("UDP, length 1206"), std::string::npos) << line;
  }
  EXPECT_EQ(count, recording.payloads.size());
  std::ifstream errors(err);
  std::stringstream text;
  text << errors.rdbuf();
  EXPECT_EQ(text.str().find("warning"), std::string::npos) << text.str();
  EXPECT_EQ(text.str().find("truncated"), std::string::npos) << text.str();
  std::remove(path.c_str());
  std::remove(out.c_str());
  std::remove(err.c_str());
}

TEST(SimRecording, TruthOnePosePerScanOrPacket) {
  const auto map = make_box_building();
  auto config = clean_config(1.0);
  Simulation per_scan(map, config);
  record(per_scan);
  const auto truth = per_scan.truth();
  ASSERT_EQ(truth.size(), 11u);  // 600 rpm: scans start every 0.1 s, and the capture's end
  EXPECT_NEAR(truth[3].time_s - truth[0].time_s, 0.3, 1e-6);
  EXPECT_NEAR(truth.back().time_s - truth.front().time_s, 1.0, 1e-6);
  config.truth_per_packet = true;
  Simulation per_packet(map, config);
  const auto recording = record(per_packet);
  EXPECT_EQ(per_packet.truth().size(), recording.payloads.size());
}

TEST(SimRecording, RejectsRpmOutsideTheSensorsRange) {
  const auto map = make_box_building();
  auto config = clean_config(1.0);
  config.sensor.rpm = 1500;
  EXPECT_THROW(Simulation(map, config), std::invalid_argument);
}

}  // namespace
}  // namespace conicloc::sim
