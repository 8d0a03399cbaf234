// libFuzzer harness: pcap / pcapng captures through the packet stream (see
// fuzz/capture_reader_input.hpp).

#include <cstdint>

#include "fuzz/capture_reader_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  conicloc::fuzz::run_capture_reader({data, size});
  return 0;
}
