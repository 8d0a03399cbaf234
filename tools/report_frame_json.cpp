#include "tools/report_frame_json.hpp"

#include <fmt/format.h>

#include <cmath>
#include <iterator>
#include <numbers>

namespace conicloc::tools {

void append_fixed(fmt::memory_buffer& out, double value, int decimals) {
  if (!std::isfinite(value)) {
    out.append(std::string_view("null"));
    return;
  }
  std::string digits = fmt::format("{:.{}f}", value, decimals);
  if (digits.find('.') != std::string::npos) {
    while (digits.back() == '0') digits.pop_back();
    if (digits.back() == '.') digits.pop_back();
  }
  if (digits == "-0") digits = "0";
  out.append(digits);
}

std::string report_frame_json(const eval::ReportFrame& frame) {
  constexpr double kRadToDeg = 180.0 / std::numbers::pi;
  fmt::memory_buffer out;
  const auto text = [&](std::string_view s) { out.append(s); };
  fmt::format_to(std::back_inserter(out), "{{\"t\":{:.6f},\"scan\":{},\"T\":[", frame.time_s,
                 frame.scan);
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 4; ++col) {
      if (row + col > 0) text(",");
      append_fixed(out, frame.T_map_sensor.matrix()(row, col), col < 3 ? 5 : 3);
    }
  }
  fmt::format_to(std::back_inserter(out), "],\"n\":{}", frame.particle_count);
  if (!frame.particles.empty()) {
    text(",\"particles\":[");
    for (std::size_t i = 0; i < frame.particles.size(); ++i) {
      const auto& p = frame.particles[i];
      if (i > 0) text(",");
      append_fixed(out, p.x, 2);
      text(",");
      append_fixed(out, p.y, 2);
      text(",");
      append_fixed(out, p.z, 2);
      text(",");
      append_fixed(out, p.yaw, 2);
    }
    text("]");
  }
  text(",\"measured\":[");
  for (std::size_t k = 0; k < frame.measured.size(); ++k) {
    text(k > 0 ? ",[" : "[");
    for (std::size_t i = 0; i < frame.measured[k].size(); ++i) {
      if (i > 0) text(",");
      append_fixed(out, frame.measured[k][i].first * kRadToDeg, 1);
      text(",");
      append_fixed(out, frame.measured[k][i].second, 2);
    }
    text("]");
  }
  text("],\"predicted\":[");
  for (std::size_t k = 0; k < frame.predicted.size(); ++k) {
    text(k > 0 ? ",[" : "[");
    for (std::size_t i = 0; i < frame.predicted[k].size(); ++i) {
      if (i > 0) text(",");
      append_fixed(out, frame.predicted[k][i], 2);
    }
    text("]");
  }
  text("]}");
  return fmt::to_string(out);
}

}  // namespace conicloc::tools
