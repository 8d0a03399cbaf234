// Live UDP input (a socket on a free port, no root) and the `conicloc decode` tool's outputs.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "io/packet_encoder.hpp"
#include "io/pcap_writer.hpp"
#include "io/udp_receiver.hpp"
#include "io/velodyne_stream.hpp"
#include "sensor/builtin_calibration.hpp"
#include "test/temp_path.hpp"

namespace conicloc::io {
namespace {

std::vector<EncodedPacket> packets(int count, double device_start_s = 10.0) {
  PacketEncoder encoder;
  for (int i = 0; i < count * 24; ++i) {
    FiringSequence s;
    s.time_s = device_start_s + i * 55.296e-6;
    s.azimuth_rad = 2.0 - 2 * M_PI * 10.0 * i * 55.296e-6;
    for (int k = 0; k < 16; ++k) {
      s.range_m[k] = k == 0 ? 0.0 : 4.0 + 0.1 * k;
      s.intensity[k] = 20;
    }
    encoder.add(s);
  }
  return encoder.take_packets();
}

TEST(UdpReceiver, ReceivesPacketsSentToItsPort) {
  UdpReceiver receiver(0, 2.0);  // any free port
  ASSERT_NE(receiver.port(), 0);
  const auto sent = packets(5);
  std::thread sender([&] {
    const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(receiver.port());
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    for (const auto& p : sent) {
      ::sendto(fd, p.payload.data(), p.payload.size(), 0, reinterpret_cast<const sockaddr*>(&to),
               sizeof to);
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    ::close(fd);
  });
  StreamConfig config;
  config.data_port = receiver.port();
  VelodyneStream stream(receiver, sensor::builtin_calibration(sensor::SensorModel::VLP16), config);
  std::vector<DecodedPoint> points;
  std::size_t received = 0;
  while (received < sent.size() && stream.next(points)) ++received;
  sender.join();
  EXPECT_EQ(received, sent.size());
  EXPECT_EQ(stream.stats().rejected_total(), 0u);
  EXPECT_NEAR(points[1].range_m, 4.1, 0.002);
}

TEST(UdpReceiver, IdleTimeoutEndsTheInput) {
  UdpReceiver receiver(0, 0.3);
  EXPECT_FALSE(receiver.next().has_value());
}

class DecodeTool : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = conicloc::test::unique_temp_path("decode_tool");
    std::filesystem::create_directories(dir_);
    capture_ = (dir_ / "run.pcap").string();
    PcapWriter writer(capture_);
    for (const auto& p : packets(200)) writer.write_udp(p.payload, 1.7e9 + p.time_s);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  int run(const std::string& args) {
    const std::string command = std::string(CONICLOC_BINARY) + " decode " + args + " > " +
                                (dir_ / "out.txt").string() + " 2>&1";
    return std::system(command.c_str());
  }
  std::string output() const {
    std::ifstream in(dir_ / "out.txt");
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  std::filesystem::path dir_;
  std::string capture_;
};

TEST_F(DecodeTool, WritesCsvPlyAndStats) {
  const std::string csv = (dir_ / "out.csv").string();
  const std::string ply = (dir_ / "ply").string();
  ASSERT_EQ(run(capture_ + " --model vlp16 --csv " + csv + " --ply " + ply + " --stats"), 0)
      << output();
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "scan,ring,azimuth_deg,range_m,intensity,time_s,x,y,z,return");
  std::size_t rows = 0;
  while (std::getline(in, line)) {
    ++rows;
    // Every row is a return with range > 0; channel 0 never returned.
    std::vector<std::string> cells;
    std::stringstream fields(line);
    for (std::string cell; std::getline(fields, cell, ',');) cells.push_back(cell);
    ASSERT_EQ(cells.size(), 10u) << line;
    const double azimuth = std::stod(cells[2]), range = std::stod(cells[3]);
    const double x = std::stod(cells[6]), y = std::stod(cells[7]);
    ASSERT_GT(range, 0.0);
    ASSERT_GE(azimuth, 0.0);
    ASSERT_LT(azimuth, 360.0);
    ASSERT_NEAR(std::atan2(y, x), std::remainder(azimuth * M_PI / 180, 2 * M_PI), 2e-3) << line;
    ASSERT_EQ(cells[9], "strongest");
  }
  EXPECT_EQ(rows, 200u * 24u * 15u);
  std::size_t ply_files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(ply)) {
    ++ply_files;
    std::ifstream file(entry.path(), std::ios::binary);
    std::getline(file, line);
    EXPECT_EQ(line, "ply");
  }
  EXPECT_EQ(ply_files, 4u);  // 2.65 turns from θ = 2 rad cross θ = 0 three times
  const std::string text = output();
  EXPECT_NE(text.find("data_packets: 200"), std::string::npos) << text;
  EXPECT_NE(text.find("return_mode: strongest"), std::string::npos);
  EXPECT_NE(text.find("rotation_rpm: 600"), std::string::npos) << text;
}

TEST_F(DecodeTool, NoDataPacketsIsAnError) {
  ASSERT_NE(run(capture_ + " --port 4000"), 0);
  EXPECT_NE(output().find("no Velodyne data packets"), std::string::npos) << output();
}

}  // namespace
}  // namespace conicloc::io
