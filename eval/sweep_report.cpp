#include "eval/sweep_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <tuple>

#include "eval/robustness_report.hpp"
#include "eval/svg_plot.hpp"
#include "eval/sweep_scenario.hpp"
#include "eval/sweep_spec.hpp"

namespace conicloc::eval {
namespace {

std::string optional_number(const std::optional<double>& value, const char* format) {
  return value ? fmt::format(fmt::runtime(format), *value) : std::string();
}

using ConfigKey = std::tuple<std::string, int, int>;

ConfigKey key_of(const RunRecord& run) {
  return {run.model, run.particles, run.beams};
}

// Horizontal RMSE of the errors from `from_s` (relative to the first) on.
double rmse_after(const TrajectoryMetrics& metrics, double from_s) {
  std::vector<double> errors;
  for (const auto& e : metrics.errors) {
    if (e.time_s - metrics.errors.front().time_s >= from_s) errors.push_back(e.xy_m);
  }
  return summarize(errors).rmse;
}

}  // namespace

std::string start_scenarios_markdown(const std::vector<RunRecord>& runs) {
  std::string md;
  for (const auto& scenario : builtin_scenarios()) {
    if (scenario.start == FilterStartMode::Tracking) continue;
    std::vector<const RunRecord*> chosen;
    for (const auto& run : runs) {
      if (run.scenario == scenario.name) chosen.push_back(&run);
    }
    if (chosen.empty()) continue;
    const bool global = scenario.start == FilterStartMode::Global;
    md += fmt::format("\n## {}: {}\n\n", global ? "Global localization" : "Kidnap recovery",
                      scenario.description);
    md += fmt::format(
        "| model | particles | beams | runs | {} | mean time to {} (s) | ATE xy RMSE "
        "once converged (m) | recoveries (mean) |\n|---|---:|---:|---:|---:|---:|"
        "---:|---:|\n",
        global ? "converged" : "recovered", global ? "converge" : "recover");
    std::vector<ConfigKey> keys;
    for (const auto* run : chosen) {
      if (std::find(keys.begin(), keys.end(), key_of(*run)) == keys.end())
        keys.push_back(key_of(*run));
    }
    for (const auto& key : keys) {
      int count = 0, succeeded = 0;
      double time_sum = 0.0, rmse_sum = 0.0, recoveries = 0.0;
      for (const auto* run : chosen) {
        if (key_of(*run) != key) continue;
        ++count;
        if (run->failed) continue;
        recoveries += static_cast<double>(run->recoveries);
        if (!run->metrics.convergence_time_s) continue;
        ++succeeded;
        time_sum += *run->metrics.convergence_time_s;
        rmse_sum += rmse_after(run->metrics, *run->metrics.convergence_time_s);
      }
      md += fmt::format("| {} | {} | {} | {} | {}/{} | {} | {} | {:.1f} |\n", std::get<0>(key),
                        setting_text(std::get<1>(key)), beams_text(std::get<2>(key)), count,
                        succeeded, count,
                        succeeded ? fmt::format("{:.1f}", time_sum / succeeded) : "—",
                        succeeded ? fmt::format("{:.4f}", rmse_sum / succeeded) : "—",
                        count ? recoveries / count : 0.0);
    }
  }
  return md;
}

std::string runs_csv(const std::vector<RunRecord>& runs) {
  std::string csv =
      "model,particles,beams,seed,scenario,ate_xy_rmse_m,heading_rmse_deg,time_per_scan_ms,"
      "realtime_factor,converged,building,ate_xy_mean_m,ate_xy_median_m,ate_xy_max_m,"
      "ate_z_rmse_m,heading_max_deg,rpe_trans_per_m,rpe_rot_deg_per_m,convergence_time_s,"
      "time_p95_ms,mean_particles,scans,recoveries,matched,missing,threads,cores,estimate,"
      "error,building_group,odometry,capture_s,false_alarms,time_to_10cm_s,lost,storeys,planes,"
      "floor_area_m2,start_time_ms,search_scans,search_time_mean_ms,search_time_max_ms,"
      "tracking_time_mean_ms,time_to_50cm_s,map_fit_xy_rmse_m,ate_xy_rmse_to_map_fit_m,"
      "map_fit_heading_rmse_deg,heading_rmse_to_map_fit_deg\n";
  for (const auto& r : runs) {
    const auto& m = r.metrics;
    std::string error = r.error;
    std::replace(error.begin(), error.end(), ',', ';');
    std::replace(error.begin(), error.end(), '\n', ' ');
    csv += fmt::format(
        "{},{},{},{},{},{:.5f},{:.4f},{:.3f},{:.3f},{},{},{:.5f},{:.5f},{:.5f},{:.5f},{:.4f},"
        "{:.6f},{:.5f},{},{:.3f},{:.1f},{},{},{},{},{},{},{},{},{},{},{:.2f},{},{},{},{},{},{:.1f},"
        "{:.3f},{},{:.3f},{:.3f},{:.3f},{},{},{},{},{}\n",
        r.model, setting_text(r.particles), setting_text(r.beams), r.seed, r.scenario,
        m.ate_xy_m.rmse, m.heading_deg.rmse, r.time_per_scan_ms, r.realtime_factor,
        r.converged ? 1 : 0, r.building, m.ate_xy_m.mean, m.ate_xy_m.median, m.ate_xy_m.max,
        m.ate_z_m.rmse, m.heading_deg.max, m.rpe_trans_per_m.rmse, m.rpe_rot_deg_per_m.rmse,
        optional_number(m.convergence_time_s, "{:.2f}"), r.time_p95_ms, r.mean_particles, r.scans,
        r.recoveries, m.matched, m.missing, r.threads, r.cores, r.estimate_file, error,
        building_group_of(r), r.odometry ? 1 : 0, r.capture_s, r.false_alarms,
        optional_number(r.time_to_10cm_s, "{:.2f}"), lost_run(r) ? 1 : 0, r.storeys, r.planes,
        r.floor_area_m2, r.start_time_ms, r.search_scans, r.search_time_mean_ms,
        r.search_time_max_ms, r.tracking_time_mean_ms, optional_number(r.time_to_50cm_s, "{:.2f}"),
        optional_number(r.map_fit_xy_rmse_m, "{:.5f}"),
        optional_number(r.ate_xy_rmse_to_map_fit_m, "{:.5f}"),
        optional_number(r.map_fit_heading_rmse_deg, "{:.4f}"),
        optional_number(r.heading_rmse_to_map_fit_deg, "{:.4f}"));
  }
  return csv;
}

std::vector<std::size_t> pareto_front(const std::vector<double>& cost,
                                      const std::vector<double>& error) {
  std::vector<std::size_t> order(std::min(cost.size(), error.size()));
  std::iota(order.begin(), order.end(), 0);
  // By cost, ties by error: a point is on the front when its error is below every cheaper one's.
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::tie(cost[a], error[a]) < std::tie(cost[b], error[b]);
  });
  std::vector<std::size_t> front;
  for (const std::size_t i : order) {
    if (!std::isfinite(cost[i]) || !std::isfinite(error[i])) continue;
    if (front.empty() || error[i] < error[front.back()]) front.push_back(i);
  }
  return front;
}

bool is_tracking(const RunRecord& run) {
  const Scenario* scenario = find_scenario(run.scenario);
  return !scenario || scenario->start == FilterStartMode::Tracking;
}

std::vector<ConfigSummary> summarize_configs(const std::vector<RunRecord>& runs) {
  std::vector<ConfigSummary> configs;
  std::map<ConfigKey, std::size_t> index;
  for (const auto& run : runs) {
    if (!is_tracking(run)) continue;
    const auto [it, inserted] = index.emplace(key_of(run), configs.size());
    if (inserted)
      configs.push_back({.model = run.model, .particles = run.particles, .beams = run.beams});
    auto& c = configs[it->second];
    ++c.runs;
    if (run.failed) continue;
    ++c.completed;
    c.succeeded += run.converged ? 1 : 0;
    c.ate_xy_rmse_m += run.metrics.ate_xy_m.rmse;
    c.heading_rmse_deg += run.metrics.heading_deg.rmse;
    c.time_per_scan_ms += run.time_per_scan_ms;
    c.realtime_factor += run.realtime_factor;
    c.time_p95_ms = std::max(c.time_p95_ms, run.time_p95_ms);
  }
  std::vector<double> cost, error;
  for (std::size_t i = 0; i < configs.size(); ++i) {
    auto& c = configs[i];
    const double n = c.completed;
    if (n > 0) {
      c.ate_xy_rmse_m /= n;
      c.heading_rmse_deg /= n;
      c.time_per_scan_ms /= n;
      c.realtime_factor /= n;
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    cost.push_back(n > 0 ? c.time_per_scan_ms : nan);
    error.push_back(n > 0 ? c.ate_xy_rmse_m : nan);
  }
  for (const std::size_t i : pareto_front(cost, error)) configs[i].pareto = true;
  return configs;
}

std::string summary_markdown(const std::vector<RunRecord>& runs, const std::string& command,
                             const std::vector<std::string>& plots) {
  std::string md = "# Evaluation sweep\n\n";
  md += fmt::format("Command: `{}`\n\n", command);
  std::set<std::string> buildings, scenarios;
  std::set<std::uint64_t> seeds;
  int failed = 0, cores = 0, threads = 0;
  for (const auto& r : runs) {
    buildings.insert(r.building);
    scenarios.insert(r.scenario);
    seeds.insert(r.seed);
    failed += r.failed ? 1 : 0;
    cores = std::max(cores, r.cores);
    threads = std::max(threads, r.threads);
  }
  md += fmt::format(
      "{} runs ({} failed): {} building(s), {} scenario(s), {} seed(s). Machine: {} hardware "
      "threads; the localizer used {}. Times are wall time per scan update; the real-time factor "
      "is capture time over processing time. Errors are against the simulator's ground truth "
      "with no alignment (the map frame is fixed).\n\n",
      runs.size(), failed, buildings.size(), scenarios.size(), seeds.size(), cores, threads);

  const auto configs = summarize_configs(runs);
  md += "## Tracking: configurations (mean over the tracking scenarios and seeds)\n\n";
  md +=
      "| model | particles | beams | runs | converged | ATE xy RMSE (m) | heading RMSE (°) | "
      "time/scan (ms) | worst p95 (ms) | real-time × | Pareto |\n";
  md += "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|:-:|\n";
  for (const auto& c : configs) {
    md += fmt::format(
        "| {} | {} | {} | {} | {}/{} | {:.4f} | {:.3f} | {:.1f} | {:.1f} | {:.1f} | {} |\n",
        c.model, setting_text(c.particles), beams_text(c.beams), c.runs, c.succeeded, c.runs,
        c.ate_xy_rmse_m, c.heading_rmse_deg, c.time_per_scan_ms, c.time_p95_ms, c.realtime_factor,
        c.pareto ? "★" : "");
  }

  md += "\n## Each model at its most accurate and at its fastest converged configuration\n\n";
  md +=
      "| model | most accurate | ATE xy RMSE (m) | time/scan (ms) | fastest converged | ATE xy "
      "RMSE (m) | time/scan (ms) |\n|---|---|---:|---:|---|---:|---:|\n";
  std::vector<std::string> models;
  for (const auto& c : configs) {
    if (std::find(models.begin(), models.end(), c.model) == models.end()) models.push_back(c.model);
  }
  for (const auto& model : models) {
    const ConfigSummary* accurate = nullptr;
    const ConfigSummary* fastest = nullptr;
    for (const auto& c : configs) {
      if (c.model != model || c.succeeded == 0) continue;
      if (!accurate || c.ate_xy_rmse_m < accurate->ate_xy_rmse_m) accurate = &c;
      if (c.succeeded == c.runs && (!fastest || c.time_per_scan_ms < fastest->time_per_scan_ms))
        fastest = &c;
    }
    const auto describe = [](const ConfigSummary* c) {
      return c ? fmt::format("{} particles, {} beams | {:.4f} | {:.1f}", setting_text(c->particles),
                             beams_text(c->beams), c->ate_xy_rmse_m, c->time_per_scan_ms)
               : std::string("— | | ");
    };
    md += fmt::format("| {} | {} | {} |\n", model, describe(accurate), describe(fastest));
  }

  md += start_scenarios_markdown(runs);
  md += robustness_markdown(runs);
  md += "\n## Every run\n\n";
  md +=
      "| building | scenario | seed | model | particles | beams | ATE xy RMSE (m) | max (m) | "
      "heading RMSE (°) | converged after (s) | recoveries | time/scan (ms) | p95 (ms) | "
      "real-time × |\n";
  md += "|---|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const auto& r : runs) {
    if (r.failed) {
      md += fmt::format("| {} | {} | {} | {} | {} | {} | failed: {} | | | | | | | |\n", r.building,
                        r.scenario, r.seed, r.model, setting_text(r.particles), beams_text(r.beams),
                        r.error);
      continue;
    }
    const auto& m = r.metrics;
    md += fmt::format(
        "| {} | {} | {} | {} | {} | {} | {:.4f} | {:.3f} | {:.3f} | {} | {} | {:.1f} | {:.1f} | "
        "{:.1f} |\n",
        r.building, r.scenario, r.seed, r.model, setting_text(r.particles), beams_text(r.beams),
        m.ate_xy_m.rmse, m.ate_xy_m.max, m.heading_deg.rmse,
        m.convergence_time_s ? fmt::format("{:.1f}", *m.convergence_time_s) : std::string("never"),
        r.recoveries, r.time_per_scan_ms, r.time_p95_ms, r.realtime_factor);
  }
  if (!plots.empty()) {
    md += "\n## Plots\n\n";
    for (const auto& plot : plots) md += fmt::format("![{0}]({0})\n\n", plot);
  }
  return md;
}

std::string pareto_svg(const std::vector<RunRecord>& runs) {
  const auto configs = summarize_configs(runs);
  std::vector<PlotSeries> series;
  std::vector<std::string> models;
  for (const auto& c : configs) {
    if (std::find(models.begin(), models.end(), c.model) == models.end()) models.push_back(c.model);
  }
  for (std::size_t m = 0; m < models.size(); ++m) {
    const std::string& model = models[m];
    PlotSeries points;
    points.label = model;
    points.colour = palette_colour(m);
    points.lines = false;
    points.markers = true;
    for (const auto& c : configs) {
      if (c.model != model || c.completed == 0) continue;
      points.x.push_back(c.time_per_scan_ms);
      points.y.push_back(c.ate_xy_rmse_m);
    }
    PlotSeries front;
    front.label = model + " front";
    front.colour = points.colour;
    front.in_legend = false;
    for (const std::size_t i : pareto_front(points.x, points.y)) {
      front.x.push_back(points.x[i]);
      front.y.push_back(points.y[i]);
    }
    series.push_back(std::move(points));
    series.push_back(std::move(front));
  }
  return render_svg_plot(
      series, {.title = "Pose error against run time: each model's configurations and Pareto front",
               .x_label = "time per scan (ms)",
               .y_label = "ATE xy RMSE (m)",
               .log_x = true,
               .log_y = true});
}

std::string error_over_time_svg(const std::vector<RunRecord>& runs, const std::string& title) {
  std::vector<PlotSeries> series;
  for (const auto& run : runs) {
    if (run.failed || run.metrics.errors.empty()) continue;
    PlotSeries s;
    s.label = fmt::format("{} ({} p, {} b)", run.model, setting_text(run.particles),
                          beams_text(run.beams));
    const double t0 = run.metrics.errors.front().time_s;
    for (const auto& e : run.metrics.errors) {
      s.x.push_back(e.time_s - t0);
      s.y.push_back(e.xy_m);
    }
    series.push_back(std::move(s));
  }
  return render_svg_plot(
      series,
      {.title = title, .x_label = "time (s)", .y_label = "horizontal error (m)", .log_y = true});
}

}  // namespace conicloc::eval
