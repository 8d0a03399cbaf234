#pragma once
// The sub-commands of the `conicloc` program. Each lives in its own tools/cmd_<name>.cpp and adds
// itself to the app; its callback throws CLI::RuntimeError(code) for a non-zero exit, or any
// std::exception, which main() reports (file and place are in the message) with exit code 1.

#include <CLI/CLI.hpp>
#include <string>

namespace conicloc::tools {

/// The shipped example building: the default for every sub-command that needs a map.
inline std::string example_map_path() {
  return CONICLOC_EXAMPLE_MAP;
}

void add_evaluate_command(CLI::App& app);
void add_predict_command(CLI::App& app);
void add_map_info_command(CLI::App& app);
void add_map_export_command(CLI::App& app);
void add_decode_command(CLI::App& app);
void add_simulate_command(CLI::App& app);
void add_localize_command(CLI::App& app);
void add_report_command(CLI::App& app);
void add_generate_building_command(CLI::App& app);
void add_replay_command(CLI::App& app);
void add_calibrate_command(CLI::App& app);

}  // namespace conicloc::tools
