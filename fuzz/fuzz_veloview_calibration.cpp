// libFuzzer harness: VeloView XML calibrations (see fuzz/veloview_calibration_input.hpp).

#include <cstdint>

#include "fuzz/veloview_calibration_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  conicloc::fuzz::run_veloview_calibration({data, size});
  return 0;
}
