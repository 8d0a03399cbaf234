// `conicloc simulate` end to end: files written, the sidecar holds the settings, same seed gives
// the same bytes, bad waypoint files are reported with file and line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/tum_trajectory.hpp"
#include "test/cli_run.hpp"
#include "test/temp_path.hpp"

namespace {

namespace fs = std::filesystem;
using conicloc::test::slurp;

int run(const std::string& arguments, const fs::path& log) {
  return conicloc::test::run_conicloc("simulate " + arguments, log);
}

class SimCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = conicloc::test::unique_temp_path("sim_cli");
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(SimCli, WritesPcapTruthOdometryAndSidecarReproducibly) {
  if (!fs::exists(CONICLOC_EXAMPLE_MAP)) GTEST_SKIP() << "no example building";
  for (const std::string name : {"a", "b"}) {
    const std::string out = (dir_ / (name + ".pcap")).string();
    const std::string args = "--out " + out + " --truth " + (dir_ / (name + ".tum")).string() +
                             " --odom " + (dir_ / (name + "_odom.tum")).string() + " --map-fit " +
                             (dir_ / (name + "_fit.tum")).string() +
                             " --duration 1 --seed 9 --clutter 2 --motion handheld"
                             " --map-error 0.05";
    ASSERT_EQ(run(args, dir_ / "log.txt"), 0) << slurp(dir_ / "log.txt");
  }
  EXPECT_EQ(slurp(dir_ / "a.pcap"), slurp(dir_ / "b.pcap"));
  EXPECT_EQ(slurp(dir_ / "a.tum"), slurp(dir_ / "b.tum"));
  EXPECT_EQ(slurp(dir_ / "a_odom.tum"), slurp(dir_ / "b_odom.tum"));
  // 1 s: 754 packets of 1248 bytes (16 pcap + 14 Ethernet + 20 IPv4 + 8 UDP + 1206) + 24 header.
  EXPECT_EQ(fs::file_size(dir_ / "a.pcap"), 24u + 754u * 1264u);
  const auto truth = conicloc::io::read_tum((dir_ / "a.tum").string());
  EXPECT_EQ(truth.size(), 11u);  // every scan start, and the end
  const auto odometry = conicloc::io::read_tum((dir_ / "a_odom.tum").string());
  EXPECT_EQ(odometry.size(), 51u);  // 50 Hz over 1 s, both ends
  // The map's pose of every truth pose (sim/map_fit.hpp): off the truth by the walls' 5 cm
  // errors, averaged over the walls in sight.
  EXPECT_EQ(slurp(dir_ / "a_fit.tum"), slurp(dir_ / "b_fit.tum"));
  const auto map_fit = conicloc::io::read_tum((dir_ / "a_fit.tum").string());
  ASSERT_EQ(map_fit.size(), truth.size());
  for (std::size_t i = 0; i < truth.size(); ++i) {
    EXPECT_EQ(map_fit[i].time_s, truth[i].time_s);
    const double off_m = (map_fit[i].pose.translation() - truth[i].pose.translation()).norm();
    EXPECT_GT(off_m, 1e-4) << i;
    EXPECT_LT(off_m, 0.25) << i;
  }
  const std::string sidecar = slurp(dir_ / "a.pcap.json");
  EXPECT_NE(sidecar.find("\"seed\":9"), std::string::npos) << sidecar;
  EXPECT_NE(sidecar.find("\"clutter_level\":2"), std::string::npos);
  EXPECT_NE(sidecar.find("\"motion\":\"handheld\""), std::string::npos);
  EXPECT_NE(sidecar.find("a_fit.tum"), std::string::npos);
}

TEST_F(SimCli, ANoiseSeedKeepsTheTruthAndRedrawsThePackets) {
  if (!fs::exists(CONICLOC_EXAMPLE_MAP)) GTEST_SKIP() << "no example building";
  for (const std::string name : {"plain", "redrawn"}) {
    const std::string args = "--out " + (dir_ / (name + ".pcap")).string() + " --truth " +
                             (dir_ / (name + ".tum")).string() + " --duration 0.5 --seed 9" +
                             (name == "redrawn" ? " --noise-seed 3" : "");
    ASSERT_EQ(run(args, dir_ / "log.txt"), 0) << slurp(dir_ / "log.txt");
  }
  EXPECT_EQ(slurp(dir_ / "plain.tum"), slurp(dir_ / "redrawn.tum"));
  EXPECT_EQ(fs::file_size(dir_ / "plain.pcap"), fs::file_size(dir_ / "redrawn.pcap"));
  EXPECT_NE(slurp(dir_ / "plain.pcap"), slurp(dir_ / "redrawn.pcap"));
  EXPECT_EQ(slurp(dir_ / "plain.pcap.json").find("noise_seed"), std::string::npos);
  EXPECT_NE(slurp(dir_ / "redrawn.pcap.json").find("\"noise_seed\":3"), std::string::npos);
}

TEST_F(SimCli, BadWaypointFileNamesFileAndLine) {
  const fs::path waypoints = dir_ / "route.txt";
  std::ofstream(waypoints) << "1 1\n2 two\n";
  const std::string args = "--out " + (dir_ / "x.pcap").string() + " --truth " +
                           (dir_ / "x.tum").string() + " --waypoints " + waypoints.string();
  EXPECT_NE(run(args, dir_ / "log.txt"), 0);
  const std::string log = slurp(dir_ / "log.txt");
  EXPECT_NE(log.find("route.txt"), std::string::npos) << log;
  EXPECT_NE(log.find("line 2"), std::string::npos) << log;
}

}  // namespace
