#pragma once
// Base64 (RFC 4648, standard alphabet, '=' padding): how JSON messages carry bytes fields
// (a JSON schema's "contentEncoding": "base64").

#include <algorithm>
#include <cstdint>
#include <span>
#include <string>

namespace conicloc::tools {

inline std::string base64(std::span<const std::uint8_t> bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string text;
  text.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    // Three bytes -> four 6-bit digits; a short last group is padded with '='.
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t group = static_cast<std::uint32_t>(bytes[i]) << 16;
    if (n > 1) group |= static_cast<std::uint32_t>(bytes[i + 1]) << 8;
    if (n > 2) group |= bytes[i + 2];
    text += kAlphabet[(group >> 18) & 63U];
    text += kAlphabet[(group >> 12) & 63U];
    text += n > 1 ? kAlphabet[(group >> 6) & 63U] : '=';
    text += n > 2 ? kAlphabet[group & 63U] : '=';
  }
  return text;
}

}  // namespace conicloc::tools
