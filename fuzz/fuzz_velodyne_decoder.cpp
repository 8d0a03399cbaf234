// libFuzzer harness: Velodyne data and position packets (see fuzz/velodyne_decoder_input.hpp).

#include <cstdint>

#include "fuzz/velodyne_decoder_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  conicloc::fuzz::run_velodyne_decoder({data, size});
  return 0;
}
