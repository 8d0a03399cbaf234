#include "tools/report_page.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "eval/report_frame.hpp"
#include "eval/trajectory_metrics.hpp"
#include "localizer/conic/pose.hpp"
#include "tools/report_frame_json.hpp"
#include "tools/report_page_html.hpp"

namespace conicloc::tools {
namespace {

constexpr std::string_view kDataMarker = "/*CONICLOC_REPORT_DATA*/";
/// Replaced by the page's size once it is known, padded with spaces to the same length.
constexpr std::string_view kSizePlaceholder = "\"@@PAGE_BYTES@@\"";

class Buffer {
 public:
  void text(std::string_view s) { out_.append(s); }
  /// `value` with `decimals` decimals, shortest text (append_fixed()).
  void number(double value, int decimals) { append_fixed(out_, value, decimals); }
  void integer(std::size_t value) { fmt::format_to(std::back_inserter(out_), "{}", value); }
  void string(std::string_view s) {
    text("\"");
    for (const char c : s) {
      if (c == '"' || c == '\\') {
        out_.push_back('\\');
        out_.push_back(c);
      } else if (static_cast<unsigned char>(c) < 0x20) {
        fmt::format_to(std::back_inserter(out_), "\\u{:04x}", static_cast<int>(c));
      } else {
        out_.push_back(c);
      }
    }
    text("\"");
  }
  template <typename Range, typename Write>
  void array(const Range& items, Write&& write) {
    text("[");
    bool first = true;
    for (const auto& item : items) {
      if (!first) text(",");
      first = false;
      write(item);
    }
    text("]");
  }
  std::string str() const { return fmt::to_string(out_); }

 private:
  fmt::memory_buffer out_;
};

void write_map(Buffer& out, const maps::PlaneMap& map, std::size_t max_polygons) {
  out.text("{\"storeys\":");
  out.array(map.storeys, [&](const maps::Storey& s) {
    out.text("{\"name\":");
    out.string(s.name);
    out.text(",\"floor_z\":");
    out.number(s.floor_z, 2);
    out.text(",\"ceiling_z\":");
    out.number(s.ceiling_z, 2);
    out.text("}");
  });
  out.text(",\"cells\":");
  out.array(map.cells, [&](const maps::Cell& c) {
    out.text("{\"storey\":");
    out.text(std::to_string(c.storey));
    out.text(",\"navigable\":");
    out.text(c.navigable ? "true" : "false");
    out.text(",\"floor_z\":");
    out.number(c.floor_z, 2);
    out.text(",\"ceiling_z\":");
    out.number(c.ceiling_z, 2);
    out.text(",\"xy\":[");
    for (std::size_t i = 0; i < c.footprint.size(); ++i) {
      if (i > 0) out.text(",");
      out.number(c.footprint[i].x(), 2);
      out.text(",");
      out.number(c.footprint[i].y(), 2);
    }
    out.text("]}");
  });
  // The 3D view's outlines: the largest polygons when there are too many to draw smoothly.
  std::vector<std::size_t> order(map.polygons.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  if (order.size() > max_polygons) {
    std::partial_sort(
        order.begin(), order.begin() + static_cast<std::ptrdiff_t>(max_polygons), order.end(),
        [&](std::size_t a, std::size_t b) { return map.polygons[a].area > map.polygons[b].area; });
    order.resize(max_polygons);
  }
  out.text(",\"polygons\":");
  out.array(order, [&](std::size_t index) {
    out.array(map.polygons[index].outer, [&](const Eigen::Vector3d& p) {
      out.number(p.x(), 2);
      out.text(",");
      out.number(p.y(), 2);
      out.text(",");
      out.number(p.z(), 2);
    });
  });
  out.text(",\"polygons_total\":");
  out.integer(map.polygons.size());
  out.text("}");
}

/// Status names in the order of their codes in the series.
constexpr std::array<std::string_view, 4> kStatuses = {"tracking", "uncertain", "lost",
                                                       "relocalizing"};

int status_code(const std::string& status) {
  for (std::size_t i = 0; i < kStatuses.size(); ++i) {
    if (kStatuses[i] == status) return static_cast<int>(i);
  }
  return 1;  // an unknown status reads as uncertain
}

void write_accuracy(Buffer& out, const ReportPageInputs& inputs) {
  std::vector<io::StampedPose> estimate;
  for (const auto& row : inputs.details) estimate.push_back({row.time_s, row.T_map_sensor});
  const eval::TrajectoryMetrics metrics = eval::evaluate_trajectory(inputs.truth, estimate);
  out.text("{\"matched\":");
  out.integer(metrics.matched);
  out.text(",\"missing\":");
  out.integer(metrics.missing);
  out.text(",\"ate_xy_rmse_m\":");
  out.number(metrics.ate_xy_m.rmse, 4);
  out.text(",\"ate_xy_median_m\":");
  out.number(metrics.ate_xy_m.median, 4);
  out.text(",\"ate_xy_max_m\":");
  out.number(metrics.ate_xy_m.max, 4);
  out.text(",\"ate_z_rmse_m\":");
  out.number(metrics.ate_z_m.rmse, 4);
  out.text(",\"heading_rmse_deg\":");
  out.number(metrics.heading_deg.rmse, 3);
  out.text(",\"convergence_time_s\":");
  if (metrics.convergence_time_s) {
    out.number(*metrics.convergence_time_s, 3);
  } else {
    out.text("null");
  }
  out.text("}");
}

void write_series(Buffer& out, const ReportPageInputs& inputs, std::size_t stride, double t0) {
  std::vector<std::size_t> rows;
  for (std::size_t i = 0; i < inputs.details.size(); i += stride) rows.push_back(i);
  const auto column = [&](std::string_view name, auto&& value, int decimals) {
    out.text(",\"");
    out.text(name);
    out.text("\":");
    out.array(rows, [&](std::size_t i) { out.number(value(inputs.details[i]), decimals); });
  };
  out.text("{\"t\":");
  out.array(rows, [&](std::size_t i) { out.number(inputs.details[i].time_s - t0, 3); });
  column(
      "x", [](const eval::DetailsRow& r) { return r.T_map_sensor.translation().x(); }, 2);
  column(
      "y", [](const eval::DetailsRow& r) { return r.T_map_sensor.translation().y(); }, 2);
  column(
      "z", [](const eval::DetailsRow& r) { return r.T_map_sensor.translation().z(); }, 2);
  column(
      "time_ms", [](const eval::DetailsRow& r) { return r.time_ms; }, 1);
  column(
      "particles", [](const eval::DetailsRow& r) { return r.particles; }, 0);
  out.text(",\"status\":");
  out.array(rows, [&](std::size_t i) { out.integer(status_code(inputs.details[i].status)); });
  // Recoveries are rare single scans: listed in full so sampling never hides one.
  out.text(",\"recovered_t\":[");
  bool first = true;
  for (const auto& row : inputs.details) {
    if (!row.recovered) continue;
    if (!first) out.text(",");
    first = false;
    out.number(row.time_s - t0, 3);
  }
  out.text("]");
  if (!inputs.truth.empty()) {
    // Horizontal error against the truth interpolated at each estimate (eval's matching rule).
    const double max_gap_s = eval::MetricsConfig{}.max_time_gap_s;
    column(
        "error_m",
        [&](const eval::DetailsRow& r) {
          const auto truth = eval::interpolate_pose(inputs.truth, r.time_s, max_gap_s);
          if (!truth) return std::numeric_limits<double>::quiet_NaN();
          return (truth->translation() - r.T_map_sensor.translation()).head<2>().norm();
        },
        3);
  }
  out.text("}");
}

void write_truth(Buffer& out, const std::vector<io::StampedPose>& truth, std::size_t max_samples,
                 double t0) {
  std::vector<std::size_t> rows;
  const std::size_t stride = eval::sampling_stride(truth.size(), max_samples);
  for (std::size_t i = 0; i < truth.size(); i += stride) rows.push_back(i);
  const auto column = [&](std::string_view name, auto&& value, int decimals) {
    out.text(name == "t" ? "\"" : ",\"");
    out.text(name);
    out.text("\":");
    out.array(rows, [&](std::size_t i) { out.number(value(truth[i]), decimals); });
  };
  out.text("{");
  column(
      "t", [&](const io::StampedPose& p) { return p.time_s - t0; }, 3);
  column(
      "x", [](const io::StampedPose& p) { return p.pose.translation().x(); }, 2);
  column(
      "y", [](const io::StampedPose& p) { return p.pose.translation().y(); }, 2);
  column(
      "z", [](const io::StampedPose& p) { return p.pose.translation().z(); }, 2);
  out.text("}");
}

}  // namespace

std::string script_safe_json(const std::string& text) {
  std::string safe;
  safe.reserve(text.size());
  for (const char c : text) {
    if (c == '<') {
      safe += "\\u003c";
    } else {
      safe.push_back(c);
    }
  }
  return safe;
}

ReportPage make_report_page(const maps::PlaneMap& map, const ReportPageInputs& inputs,
                            const ReportPageLimits& limits) {
  if (inputs.details.empty()) throw std::invalid_argument("the run has no localized scan");
  ReportPage page;
  page.frame_stride = eval::sampling_stride(inputs.frames.size(), limits.max_frames);
  page.series_stride = eval::sampling_stride(inputs.details.size(), limits.max_series);
  const double t0 = inputs.details.front().time_s;

  Buffer data;
  data.text("{\"title\":");
  data.string(inputs.title);
  data.text(",\"t0\":");
  data.number(t0, 6);
  data.text(",\"run\":");
  data.text(inputs.run_json);
  data.text(",\"sampling\":{\"scans\":");
  data.integer(inputs.details.size());
  data.text(",\"frame_every\":");
  data.integer(inputs.frame_every * page.frame_stride);
  data.text(",\"frames_recorded\":");
  data.integer(inputs.frames.size());
  data.text(",\"series_every\":");
  data.integer(page.series_stride);
  data.text(",\"particles_recorded\":");
  data.text(inputs.particles_recorded ? "true" : "false");
  data.text("},\"accuracy\":");
  if (inputs.truth.empty()) {
    data.text("null");
  } else {
    write_accuracy(data, inputs);
  }
  data.text(",\"statuses\":");
  data.array(kStatuses, [&](std::string_view name) { data.string(name); });
  data.text(",\"map\":");
  write_map(data, map, limits.max_polygons);
  data.text(",\"series\":");
  write_series(data, inputs, page.series_stride, t0);
  data.text(",\"truth\":");
  if (inputs.truth.empty()) {
    data.text("null");
  } else {
    write_truth(data, inputs.truth, limits.max_series, t0);
  }
  data.text(",\"frames\":[");
  for (std::size_t i = 0; i < inputs.frames.size(); i += page.frame_stride) {
    if (page.frames_embedded++ > 0) data.text(",");
    data.text(inputs.frames[i]);
  }
  data.text("],\"page_bytes\":");
  data.text(kSizePlaceholder);
  data.text("}");

  const std::string_view html_template = kReportPageHtml;
  const std::size_t marker = html_template.find(kDataMarker);
  if (marker == std::string_view::npos)
    throw std::logic_error("report template has no data marker");
  const std::string json = script_safe_json(data.str());
  page.html.reserve(html_template.size() + json.size());
  page.html.append(html_template.substr(0, marker));
  page.html.append(json);
  page.html.append(html_template.substr(marker + kDataMarker.size()));

  const std::size_t at = page.html.rfind(kSizePlaceholder);
  const std::string size = fmt::format("{:>{}}", page.html.size(), kSizePlaceholder.size());
  if (size.size() != kSizePlaceholder.size()) throw std::logic_error("page too large to state");
  page.html.replace(at, kSizePlaceholder.size(), size);
  return page;
}

}  // namespace conicloc::tools
