// libFuzzer harness: velodyne_msgs/VelodyneScan messages, ROS 1 and CDR (see
// fuzz/bag_reader_input.hpp).

#include <cstdint>

#include "fuzz/bag_reader_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  conicloc::fuzz::run_velodyne_scan_msg({data, size});
  return 0;
}
