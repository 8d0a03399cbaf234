#include "tools/evaluate_sweep.hpp"

#include <spdlog/spdlog.h>

namespace conicloc::tools {

int run_logged_sweep(const run::SweepOptions& options) {
  run::SweepProgress progress;
  progress.warning = [](const std::string& message) { spdlog::warn("{}", message); };
  progress.error = [](const std::string& message) { spdlog::error("{}", message); };
  progress.started = [&](const run::SweepOutline& outline) {
    spdlog::info("sweep '{}': {} runs ({} recordings x {} localizer settings) into {}",
                 options.spec.name, outline.runs, outline.recordings, outline.settings,
                 options.out_dir);
    if (options.shard) {
      spdlog::info("shard {}: {} of the runs, {} held already, {} to make", options.shard->text(),
                   outline.held + outline.to_make, outline.held, outline.to_make);
    }
  };
  progress.run_done = [](const run::SweepRunDone& run) {
    const eval::RunRecord& record = *run.record;
    spdlog::info(
        "[{}/{}] {} {} s{} {} p{} b{}: ATE xy {:.3f} m (max {:.3f}), heading {:.2f} deg, "
        "{:.1f} ms/scan, {} recoveries ({} false), {}",
        run.done, run.share, run.building, run.scenario->name, run.seed, run.setting.model,
        eval::setting_text(run.setting.particles), eval::setting_text(run.setting.beams),
        record.metrics.ate_xy_m.rmse, record.metrics.ate_xy_m.max, record.metrics.heading_deg.rmse,
        record.time_per_scan_ms, record.recoveries, record.false_alarms,
        record.failed ? "FAILED: " + record.error
                      : (record.converged ? "converged" : "not converged"));
  };
  const run::SweepResult result = run::run_sweep(options, progress);
  if (options.shard) {
    spdlog::info("shard {}: wrote {}/runs.csv ({} runs); merge the shards with --merge",
                 options.shard->text(), options.out_dir, result.runs.size());
  } else {
    spdlog::info("wrote {}/runs.csv, summary.md, robustness.md and plots", options.out_dir);
  }
  return result.failed;
}

}  // namespace conicloc::tools
