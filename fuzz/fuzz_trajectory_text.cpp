// libFuzzer harness: TUM trajectory and waypoint files (see fuzz/trajectory_text_input.hpp).

#include <cstdint>

#include "fuzz/trajectory_text_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  conicloc::fuzz::run_trajectory_text({data, size});
  return 0;
}
