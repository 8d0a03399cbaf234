// libFuzzer harness: the IndoorGML map loader (see fuzz/indoorgml_input.hpp).

#include <cstdint>

#include "fuzz/indoorgml_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  conicloc::fuzz::run_indoorgml({data, size});
  return 0;
}
