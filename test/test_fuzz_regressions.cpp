// Replays the fuzzers' committed seeds and every fixed finding (test/data/fuzz_regressions, named
// <target>-<what>) through the same drivers the libFuzzer harnesses run (fuzz/*_input.hpp), in
// the normal build: each input must be accepted or refused with io::InputError, never crash or
// break a documented guarantee. Findings with a specific expected outcome have their own case.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz/bag_reader_input.hpp"
#include "fuzz/capture_reader_input.hpp"
#include "fuzz/indoorgml_input.hpp"
#include "fuzz/point_cloud2_input.hpp"
#include "fuzz/trajectory_text_input.hpp"
#include "fuzz/velodyne_decoder_input.hpp"
#include "fuzz/veloview_calibration_input.hpp"
#include "io/mcap_reader.hpp"
#include "io/ros2_db3_reader.hpp"
#include "io/rosbag1_reader.hpp"

namespace {

namespace fs = std::filesystem;

const fs::path kCorpusDir = fs::path(CONICLOC_TEST_DATA) / ".." / ".." / "fuzz" / "corpus";
const fs::path kRegressionDir = fs::path(CONICLOC_TEST_DATA) / "fuzz_regressions";

std::vector<std::uint8_t> read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The committed seeds of `target` and its regression inputs, sorted.
std::vector<fs::path> inputs_of(const std::string& target) {
  std::vector<fs::path> paths;
  if (fs::is_directory(kCorpusDir / target)) {
    for (const auto& entry : fs::directory_iterator(kCorpusDir / target)) {
      paths.push_back(entry.path());
    }
  }
  const std::string prefix = target.substr(std::string("fuzz_").size()) + "-";
  if (fs::is_directory(kRegressionDir)) {
    for (const auto& entry : fs::directory_iterator(kRegressionDir)) {
      if (entry.path().filename().string().rfind(prefix, 0) == 0) paths.push_back(entry.path());
    }
  }
  std::sort(paths.begin(), paths.end());
  return paths;
}

void replay(const std::string& target,
            const std::function<void(std::span<const std::uint8_t>)>& driver) {
  const auto paths = inputs_of(target);
  ASSERT_FALSE(paths.empty()) << "no seeds in " << (kCorpusDir / target);
  for (const auto& path : paths) {
    const auto bytes = read_bytes(path);
    EXPECT_NO_THROW(driver(bytes)) << path;
  }
}

TEST(FuzzCorpusReplay, VelodyneDecoder) {
  replay("fuzz_velodyne_decoder", conicloc::fuzz::run_velodyne_decoder);
}

TEST(FuzzCorpusReplay, CaptureReader) {
  replay("fuzz_capture_reader", conicloc::fuzz::run_capture_reader);
}

// The bag fuzzers' seeds are replayed, and each committed seed is a bag the reader reads
// messages from (a seed the reader refused would leave the fuzzer nothing to mutate).
template <class Reader, class File = conicloc::fuzz::MemoryFile>
void replay_bags(const std::string& target) {
  replay(target, [](std::span<const std::uint8_t> bytes) {
    (void)conicloc::fuzz::run_bag_reader<Reader, File>(bytes);
  });
  for (const auto& entry : fs::directory_iterator(kCorpusDir / target)) {
    EXPECT_GT((conicloc::fuzz::run_bag_reader<Reader, File>(read_bytes(entry.path()))), 0u)
        << entry.path();
  }
}

TEST(FuzzCorpusReplay, McapReader) {
  replay_bags<conicloc::io::McapReader>("fuzz_mcap_reader");
}

TEST(FuzzCorpusReplay, Rosbag1Reader) {
  replay_bags<conicloc::io::Rosbag1Reader>("fuzz_rosbag1_reader");
}

TEST(FuzzCorpusReplay, Ros2Db3Reader) {
  replay_bags<conicloc::io::Ros2Db3Reader, conicloc::fuzz::TempFile>("fuzz_ros2_db3_reader");
}

TEST(FuzzCorpusReplay, VelodyneScanMessage) {
  replay("fuzz_velodyne_scan_msg", conicloc::fuzz::run_velodyne_scan_msg);
}

TEST(FuzzCorpusReplay, PointCloud2) {
  replay("fuzz_point_cloud2", conicloc::fuzz::run_point_cloud2);
}

TEST(FuzzCorpusReplay, IndoorGml) {
  replay("fuzz_indoorgml", conicloc::fuzz::run_indoorgml);
}

TEST(FuzzCorpusReplay, TrajectoryText) {
  replay("fuzz_trajectory_text", conicloc::fuzz::run_trajectory_text);
}

TEST(FuzzCorpusReplay, VeloviewCalibration) {
  replay("fuzz_veloview_calibration", conicloc::fuzz::run_veloview_calibration);
}

}  // namespace
