// `conicloc evaluate --truth truth.tum --est poses.tum`: scores any trajectory file against truth.
#include <spdlog/spdlog.h>

#include <filesystem>
#include <fstream>

#include "eval/sweep_shard.hpp"
#include "eval/sweep_spec.hpp"
#include "eval/trajectory_metrics.hpp"
#include "io/input_error.hpp"
#include "io/tum_trajectory.hpp"
#include "tools/commands.hpp"
#include "tools/evaluate_sweep.hpp"
#include "tools/map_options.hpp"
#include "tools/sweep_merge.hpp"

namespace conicloc::tools {
namespace {

struct EvaluateOptions {
  std::string map_path;
  std::string sweep = "quick";
  std::string out_dir;
  std::string command;
  std::string truth_path;
  std::string estimate_path;
  std::string errors_csv;
  std::string shard;                    ///< I/N; empty: the whole sweep
  std::vector<std::string> merge_dirs;  ///< shards' folders to merge into out_dir
  eval::MetricsConfig metrics;
  io::MapLoadOptions map_options;  ///< how the sweep's --map file is read
};

void log_stats(const char* name, const eval::ErrorStats& s, const char* unit) {
  spdlog::info("{:<22} rmse {:9.4f}  mean {:9.4f}  median {:9.4f}  max {:9.4f} {} (n={})", name,
               s.rmse, s.mean, s.median, s.max, unit, s.count);
}

void write_errors_csv(const std::string& path, const eval::TrajectoryMetrics& metrics) {
  std::ofstream out(path);
  if (!out) throw io::InputError(path, "", "cannot write error CSV");
  out << "time_s,xy_m,z_m,heading_deg\n";
  for (const auto& e : metrics.errors) {
    out << fmt::format("{:.6f},{:.6f},{:.6f},{:.6f}\n", e.time_s, e.xy_m, e.z_m, e.heading_deg);
  }
}

// The public IndoorGML models the robustness sweep runs on, beside the source tree.
std::string public_models_dir() {
  return (std::filesystem::path(CONICLOC_SHARED_DATA) / "indoorgml").string();
}

// Runs a sweep or a merge (`body` returns its failed runs): shards that do not fit together
// exit 2, failed runs exit 3, each with its message.
template <class Body>
void exit_on_failures(Body body, const std::string& out_dir) {
  int failed = 0;
  try {
    failed = body();
  } catch (const eval::ShardError& e) {
    spdlog::error("{}", e.what());
    throw CLI::RuntimeError(2);
  }
  if (failed > 0) {
    spdlog::error("{} runs failed (see {}/runs.csv)", failed, out_dir);
    throw CLI::RuntimeError(3);
  }
}

void run_evaluate_sweep(const EvaluateOptions& options) {
  run::SweepOptions sweep;
  sweep.map_path = options.map_path.empty() ? example_map_path() : options.map_path;
  sweep.map_options = options.map_options;
  sweep.out_dir = options.out_dir;
  sweep.command = options.command;
  sweep.spec = eval::resolve_sweep(options.sweep, public_models_dir());
  sweep.metrics = options.metrics;
  if (!options.shard.empty()) sweep.shard = eval::parse_shard(options.shard);
  exit_on_failures([&] { return run_logged_sweep(sweep); }, options.out_dir);
}

void run_evaluate_merge(const EvaluateOptions& options) {
  if (options.out_dir.empty()) throw CLI::ValidationError("--merge", "give --out DIR");
  if (!options.truth_path.empty() || !options.estimate_path.empty() || !options.map_path.empty())
    throw CLI::ValidationError("--merge",
                               "takes the sweep from the shards: no --truth, --est or --map");
  MergeOptions merge;
  merge.shard_dirs = options.merge_dirs;
  merge.out_dir = options.out_dir;
  merge.command = options.command;
  exit_on_failures([&] { return merge_sweep(merge); }, options.out_dir);
}

void run_evaluate(const EvaluateOptions& options) {
  if (!options.merge_dirs.empty()) {
    run_evaluate_merge(options);
    return;
  }
  if (!options.shard.empty() && options.out_dir.empty())
    throw CLI::ValidationError("--shard", "a shard of a sweep needs --out DIR");
  if (!options.out_dir.empty()) {
    if (!options.truth_path.empty() || !options.estimate_path.empty()) {
      throw CLI::ValidationError("--out", "a sweep (--out DIR) takes no --truth/--est");
    }
    run_evaluate_sweep(options);
    return;
  }
  if (options.truth_path.empty() || options.estimate_path.empty()) {
    throw CLI::ValidationError(
        "evaluate", "give --truth and --est to score a trajectory, or --out DIR to run a sweep");
  }
  const auto truth = io::read_tum(options.truth_path);
  const auto estimate = io::read_tum(options.estimate_path);
  if (truth.empty()) throw io::InputError(options.truth_path, "", "no poses in the file");
  if (estimate.empty()) throw io::InputError(options.estimate_path, "", "no poses in the file");
  const auto metrics = eval::evaluate_trajectory(truth, estimate, options.metrics);
  spdlog::info("{} estimates, {} matched to truth, {} without truth", metrics.estimates,
               metrics.matched, metrics.missing);
  log_stats("ATE xy", metrics.ate_xy_m, "m");
  log_stats("ATE z", metrics.ate_z_m, "m");
  log_stats("heading", metrics.heading_deg, "deg");
  log_stats("RPE translation", metrics.rpe_trans_per_m, "m/m");
  log_stats("RPE rotation", metrics.rpe_rot_deg_per_m, "deg/m");
  if (metrics.convergence_time_s) {
    spdlog::info("converged after {:.2f} s", *metrics.convergence_time_s);
  } else {
    spdlog::info("never converged (xy < {} m and heading < {} deg to the end)",
                 options.metrics.converged_xy_m, options.metrics.converged_heading_deg);
  }
  if (!options.errors_csv.empty()) write_errors_csv(options.errors_csv, metrics);
  if (metrics.matched == 0) throw CLI::RuntimeError(2);
}

}  // namespace

void add_evaluate_command(CLI::App& app) {
  auto options = std::make_shared<EvaluateOptions>();
  auto* cmd = app.add_subcommand(
      "evaluate",
      "Score an estimated trajectory against ground truth (--truth, --est), or run an evaluation "
      "sweep: simulate, localize and score (--map, --sweep, --out)");
  cmd->add_option("--truth", options->truth_path, "Ground-truth TUM file")
      ->check(CLI::ExistingFile);
  cmd->add_option("--est", options->estimate_path, "Estimated TUM file")->check(CLI::ExistingFile);
  cmd->add_option("--map", options->map_path,
                  "Sweep: IndoorGML building or generated:KIND[:SEED] (default: the example "
                  "building)")
      ->check(CLI::ExistingFile | CLI::Validator(
                                      [](const std::string& map) {
                                        return eval::is_generated_map(map) ? std::string()
                                                                           : "not generated:";
                                      },
                                      "generated:KIND[:SEED]"));
  add_map_load_options(cmd, options->map_options);
  cmd->add_option("--sweep", options->sweep,
                  "Sweep: quick, full, robustness, scale, or a sweep file")
      ->capture_default_str();
  cmd->add_option("--out", options->out_dir,
                  "Sweep: output folder for runs.csv, summary.md, robustness.md and the SVG "
                  "plots");
  auto* shard =
      cmd->add_option("--shard", options->shard,
                      "Sweep: run only shard I of N (1-based: 1/4 ... 4/4), the runs whose index "
                      "is I-1 modulo N; resumes from DIR/runs.csv; merge the shards with --merge")
          ->check(CLI::Validator(
              [](const std::string& text) {
                try {
                  eval::parse_shard(text);
                  return std::string();
                } catch (const std::invalid_argument& e) {
                  return std::string(e.what());
                }
              },
              "I/N"));
  cmd->add_option("--merge", options->merge_dirs,
                  "Merge the shards' folders (each run with --shard I/N) into --out: the whole "
                  "sweep's runs.csv, summary.md, robustness.md and plots")
      ->expected(1, -1)
      ->excludes(shard);
  cmd->add_option("--errors", options->errors_csv, "Write per-pose errors (CSV)");
  cmd->add_option("--max-time-gap", options->metrics.max_time_gap_s,
                  "Seconds an estimate may lie from truth samples")
      ->capture_default_str();
  cmd->add_option("--rpe-delta", options->metrics.rpe_delta_m,
                  "Relative pose error over this many metres")
      ->capture_default_str();
  cmd->callback([options, cmd] {
    options->command = "conicloc evaluate";
    for (const auto* option : cmd->get_options()) {
      if (option->count() == 0 || option->get_name() == "--help") continue;
      options->command += " " + option->get_name();
      for (const auto& value : option->results()) options->command += " " + value;
    }
    run_evaluate(*options);
  });
}

}  // namespace conicloc::tools
