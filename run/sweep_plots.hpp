#pragma once
// The SVG charts of an evaluation sweep report: the Pareto front of error against time per scan,
// and for one building per scenario the error over time and the floor plan with the truth and
// each model's estimated path.

#include <filesystem>
#include <string>
#include <vector>

#include "eval/sweep_report.hpp"
#include "run/sweep_buildings.hpp"

namespace conicloc::run {

/// Writes pareto.svg and, per scenario of `plotted`, error_over_time_<scenario>.svg and
/// trajectory_<scenario>.svg (each model's largest configuration on the scenario's first
/// recording) into `out_dir`; returns their names. Reads the truth and estimate files from
/// `out_dir`/runs.
std::vector<std::string> write_plots(const Building& plotted,
                                     const std::vector<eval::RunRecord>& runs,
                                     const std::filesystem::path& out_dir);

}  // namespace conicloc::run
