// libFuzzer harness: sensor_msgs/PointCloud2 messages (see fuzz/point_cloud2_input.hpp).

#include <cstdint>

#include "fuzz/point_cloud2_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  conicloc::fuzz::run_point_cloud2({data, size});
  return 0;
}
