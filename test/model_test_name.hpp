#pragma once
// The name of a test instantiated per observation model: gtest names allow no '-'.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace conicloc::test {

inline std::string model_test_name(const ::testing::TestParamInfo<std::string>& model) {
  std::string name = model.param;
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

}  // namespace conicloc::test
