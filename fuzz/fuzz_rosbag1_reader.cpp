// libFuzzer harness: io::Rosbag1Reader alone, topics and every message of one topic (see
// fuzz/bag_reader_input.hpp).

#include <cstdint>

#include "fuzz/bag_reader_input.hpp"
#include "io/rosbag1_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  (void)conicloc::fuzz::run_bag_reader<conicloc::io::Rosbag1Reader>({data, size});
  return 0;
}
