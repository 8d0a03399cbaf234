#include "eval/scale_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "eval/robustness_report.hpp"
#include "eval/svg_plot.hpp"
#include "eval/sweep_spec.hpp"

namespace conicloc::eval {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

// Sums of one row's runs, turned into means by finish().
struct RowSums {
  ScaleRow row;
  int tracked = 0, searched = 0;
  double tracking_sum = 0.0, search_sum = 0.0, start_sum = 0.0, realtime_sum = 0.0;
  double settle_sum = 0.0;

  void add(const RunRecord& run, double settle_within_s) {
    ++row.runs;
    if (run.search_scans > 0) {
      ++searched;
      search_sum += run.search_time_mean_ms;
      row.search_time_max_ms = std::max(row.search_time_max_ms, run.search_time_max_ms);
    }
    if (run.search_scans < run.scans) {
      ++tracked;
      tracking_sum += run.tracking_time_mean_ms;
    }
    start_sum += run.start_time_ms;
    realtime_sum += run.realtime_factor;
    if (run.time_to_10cm_s && *run.time_to_10cm_s <= settle_within_s) {
      ++row.settled;
      settle_sum += *run.time_to_10cm_s;
    }
  }

  ScaleRow finish() const {
    ScaleRow out = row;
    const auto mean = [](double sum, int n) { return n > 0 ? sum / n : kNan; };
    out.tracking_time_mean_ms = mean(tracking_sum, tracked);
    out.search_time_mean_ms = mean(search_sum, searched);
    out.start_time_ms = mean(start_sum, row.runs);
    out.realtime_factor = mean(realtime_sum, row.runs);
    out.settle_time_mean_s = mean(settle_sum, row.settled);
    return out;
  }
};

std::string number_or_dash(double value, const char* format) {
  return std::isfinite(value) ? fmt::format(fmt::runtime(format), value) : std::string("—");
}

}  // namespace

std::vector<ScaleRow> scale_rows(const std::vector<RunRecord>& runs) {
  const double settle_within_s = RobustnessTargets{}.settle_within_s;
  std::vector<RowSums> sums;
  for (const auto& run : runs) {
    if (run.failed || run.planes == 0) continue;
    auto it = std::find_if(sums.begin(), sums.end(), [&](const RowSums& s) {
      return s.row.model == run.model && s.row.particles == run.particles &&
             s.row.beams == run.beams && s.row.scenario == run.scenario &&
             s.row.building == run.building;
    });
    if (it == sums.end()) {
      RowSums fresh;
      fresh.row.model = run.model;
      fresh.row.particles = run.particles;
      fresh.row.beams = run.beams;
      fresh.row.scenario = run.scenario;
      fresh.row.building = run.building;
      fresh.row.storeys = run.storeys;
      fresh.row.planes = run.planes;
      fresh.row.floor_area_m2 = run.floor_area_m2;
      sums.push_back(fresh);
      it = sums.end() - 1;
    }
    it->add(run, settle_within_s);
  }
  std::vector<ScaleRow> rows;
  for (const auto& s : sums) rows.push_back(s.finish());
  std::stable_sort(rows.begin(), rows.end(), [](const ScaleRow& a, const ScaleRow& b) {
    return std::tie(a.model, a.particles, a.beams, a.scenario, a.floor_area_m2, a.storeys) <
           std::tie(b.model, b.particles, b.beams, b.scenario, b.floor_area_m2, b.storeys);
  });
  return rows;
}

std::string scale_markdown(const std::vector<RunRecord>& runs) {
  const auto rows = scale_rows(runs);
  std::string md =
      "\n## Cost against building size (per model, scenario and building, over seeds)\n\n"
      "Searching: the scans from a global start, or from any scan that ended unsure or lost, up "
      "to and including the one that ended `tracking`; tracking: the others. Start: before the "
      "first scan (a global start's plan-search fields). "
      "Settled: at ≤ 10 cm within 10 s.\n\n";
  if (rows.empty()) return md + "No completed run with the building's size.\n";
  md +=
      "| model | particles | beams | scenario | building | storeys | planes | floor area (m²) | "
      "runs | tracking (ms/scan) | searching (ms/scan) | searching max (ms) | start (ms) | real "
      "time (×) | settled | settled after (s) |\n"
      "|---|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const auto& r : rows) {
    md += fmt::format(
        "| {} | {} | {} | {} | {} | {} | {} | {:.0f} | {} | {} | {} | {} | {:.0f} | {:.2f} | {}/{} "
        "| {} |\n",
        r.model, setting_text(r.particles), setting_text(r.beams), r.scenario, r.building,
        r.storeys, r.planes, r.floor_area_m2, r.runs,
        number_or_dash(r.tracking_time_mean_ms, "{:.1f}"),
        number_or_dash(r.search_time_mean_ms, "{:.1f}"),
        r.search_time_max_ms > 0.0 ? fmt::format("{:.0f}", r.search_time_max_ms) : "—",
        r.start_time_ms, r.realtime_factor, r.settled, r.runs,
        number_or_dash(r.settle_time_mean_s, "{:.1f}"));
  }
  return md;
}

std::string scale_svg(const std::vector<RunRecord>& runs) {
  const auto rows = scale_rows(runs);
  std::vector<PlotSeries> series;
  // One colour per model × scenario: tracking as a line, searching as markers.
  std::vector<std::string> keys;
  for (const auto& r : rows) {
    std::string key = r.model;
    if (r.particles != kDefaultSetting || r.beams != kDefaultSetting)
      key += " (" + setting_text(r.particles) + " p, " + setting_text(r.beams) + " b)";
    key += ", " + r.scenario;
    auto key_it = std::find(keys.begin(), keys.end(), key);
    if (key_it == keys.end()) {
      keys.push_back(key);
      const std::string colour = palette_colour(keys.size() - 1);
      PlotSeries tracking;
      tracking.label = key + ": tracking";
      tracking.colour = colour;
      PlotSeries searching = tracking;
      searching.label = key + ": searching";
      searching.lines = false;
      searching.markers = true;
      series.push_back(std::move(tracking));
      series.push_back(std::move(searching));
      key_it = keys.end() - 1;
    }
    const std::size_t k = 2 * static_cast<std::size_t>(key_it - keys.begin());
    series[k].x.push_back(r.floor_area_m2);
    series[k].y.push_back(r.tracking_time_mean_ms);
    series[k + 1].x.push_back(r.floor_area_m2);
    series[k + 1].y.push_back(r.search_time_mean_ms);
  }
  return render_svg_plot(series, {.title = "Time per scan against building size",
                                  .x_label = "navigable floor area (m²)",
                                  .y_label = "time per scan (ms)",
                                  .log_x = true,
                                  .log_y = true});
}

}  // namespace conicloc::eval
