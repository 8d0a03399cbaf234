#pragma once
// What the fuzz drivers throw when an accepted input breaks a documented guarantee (a decoded
// azimuth outside [0, 2π), a non-finite pose...). Under libFuzzer it is uncaught and aborts (a
// finding); test/test_fuzz_regressions.cpp replays the corpora and expects none.

#include <stdexcept>
#include <string>

namespace conicloc::fuzz {

class ContractViolation : public std::logic_error {
 public:
  explicit ContractViolation(const std::string& what) : std::logic_error(what) {}
};

inline void require(bool condition, const char* what) {
  if (!condition) throw ContractViolation(what);
}

}  // namespace conicloc::fuzz
