// libFuzzer harness: io::Ros2Db3Reader alone, topics and every message of one topic (see
// fuzz/bag_reader_input.hpp); the input goes to a file on disk, which SQLite can open.

#include <cstdint>

#include "fuzz/bag_reader_input.hpp"
#include "io/ros2_db3_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  (void)conicloc::fuzz::run_bag_reader<conicloc::io::Ros2Db3Reader, conicloc::fuzz::TempFile>(
      {data, size});
  return 0;
}
