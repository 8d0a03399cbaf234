#include "run/sweep_plots.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <optional>
#include <tuple>

#include "eval/sweep_plan.hpp"
#include "eval/sweep_report.hpp"
#include "eval/sweep_spec.hpp"
#include "io/input_error.hpp"
#include "io/map_export.hpp"
#include "io/tum_trajectory.hpp"

namespace conicloc::run {
namespace {

namespace fs = std::filesystem;

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  out.flush();
  if (!out) throw io::InputError(path.string(), "", "cannot write");
}

// The runs to show over time and over the plan: per model its largest configuration on the
// first recording of the given scenario.
std::vector<eval::RunRecord> showcase_runs(const std::vector<eval::RunRecord>& runs,
                                           const std::string& building,
                                           const std::string& scenario) {
  std::vector<eval::RunRecord> chosen;
  std::optional<std::uint64_t> seed;
  for (const auto& run : runs) {
    if (run.building != building || run.scenario != scenario || run.failed) continue;
    if (!seed) seed = run.seed;
    if (run.seed != *seed) continue;
    auto it = std::find_if(chosen.begin(), chosen.end(),
                           [&](const eval::RunRecord& c) { return c.model == run.model; });
    if (it == chosen.end()) {
      chosen.push_back(run);
    } else if (std::tie(run.particles, run.beams) > std::tie(it->particles, it->beams)) {
      *it = run;
    }
  }
  return chosen;
}

std::string trajectory_plan_svg(const Building& building, const std::vector<eval::RunRecord>& runs,
                                const fs::path& out_dir, const std::string& truth_path) {
  static const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e"};
  io::FloorPlanOptions options;
  options.show_navigation = false;
  const auto to_path = [](const std::vector<io::StampedPose>& poses) {
    std::vector<Eigen::Vector3d> points;
    for (const auto& p : poses) points.push_back(p.pose.translation());
    return points;
  };
  options.paths.push_back({.label = "truth",
                           .colour = "#222222",
                           .width_px = 2.4,
                           .dashed = false,
                           .points = to_path(io::read_tum(truth_path))});
  std::size_t k = 0;
  for (const auto& run : runs) {
    options.paths.push_back(
        {.label = fmt::format("{} ({} p)", run.model, eval::setting_text(run.particles)),
         .colour = kColours[k++ % std::size(kColours)],
         .width_px = 1.4,
         .dashed = true,
         .points = to_path(io::read_tum((out_dir / run.estimate_file).string()))});
  }
  return io::render_floor_plan_svg(building.map, options);
}

}  // namespace

std::vector<std::string> write_plots(const Building& plotted,
                                     const std::vector<eval::RunRecord>& runs,
                                     const fs::path& out_dir) {
  std::vector<std::string> plots;
  write_text(out_dir / "pareto.svg", eval::pareto_svg(runs));
  plots.push_back("pareto.svg");
  std::vector<std::string> scenarios;
  for (const auto& run : runs) {
    if (run.building == plotted.name &&
        std::find(scenarios.begin(), scenarios.end(), run.scenario) == scenarios.end())
      scenarios.push_back(run.scenario);
  }
  for (const auto& scenario : scenarios) {
    const auto shown = showcase_runs(runs, plotted.name, scenario);
    if (shown.empty()) continue;
    const std::string recording = eval::recording_name(plotted.name, scenario, shown.front().seed);
    const std::string errors_name = "error_over_time_" + scenario + ".svg";
    write_text(out_dir / errors_name,
               eval::error_over_time_svg(shown, "Horizontal error along " + recording));
    plots.push_back(errors_name);
    const std::string plan_name = "trajectory_" + scenario + ".svg";
    write_text(out_dir / plan_name,
               trajectory_plan_svg(plotted, shown, out_dir,
                                   (out_dir / "runs" / (recording + eval::kTruthSuffix)).string()));
    plots.push_back(plan_name);
  }
  return plots;
}

}  // namespace conicloc::run
