#pragma once
// `conicloc evaluate --map FILE --sweep quick|full|robustness|FILE --out DIR`: the sweep of
// run/sweep_runner.hpp, its progress logged.

#include "run/sweep_runner.hpp"

namespace conicloc::tools {

/// Runs the sweep, logging every run and what went wrong; returns the number of failed runs (of
/// this shard's runs made now). Throws what run::run_sweep() throws.
int run_logged_sweep(const run::SweepOptions& options);

}  // namespace conicloc::tools
