// tools/base64.hpp: the test vectors of RFC 4648 (section 10), and every byte value.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tools/base64.hpp"

namespace conicloc::tools {
namespace {

std::string encode(const std::string& text) {
  return base64(std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

TEST(Base64, Rfc4648TestVectors) {
  EXPECT_EQ(encode(""), "");
  EXPECT_EQ(encode("f"), "Zg==");
  EXPECT_EQ(encode("fo"), "Zm8=");
  EXPECT_EQ(encode("foo"), "Zm9v");
  EXPECT_EQ(encode("foob"), "Zm9vYg==");
  EXPECT_EQ(encode("fooba"), "Zm9vYmE=");
  EXPECT_EQ(encode("foobar"), "Zm9vYmFy");
}

TEST(Base64, HighBytesUseTheLastDigits) {
  const std::vector<std::uint8_t> bytes = {0xFB, 0xFF, 0xBF, 0x00, 0x10, 0x83};
  EXPECT_EQ(base64(bytes), "+/+/ABCD");
}

}  // namespace
}  // namespace conicloc::tools
