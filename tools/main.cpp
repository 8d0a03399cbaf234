// conicloc: localize a spinning multi-beam LiDAR in an IndoorGML building model.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <exception>

#include "tools/commands.hpp"

int main(int argc, char** argv) {
  // Messages go to stderr, so stdout holds only a command's output (CSV, JSON, --stats).
  spdlog::set_default_logger(spdlog::stderr_color_mt("conicloc"));
  CLI::App app{"conicloc: projective-conic LiDAR localization in IndoorGML building models"};
  app.set_version_flag("--version", "conicloc 0.1.0");
  app.require_subcommand(1);
  bool verbose = false;
  app.add_flag("-v,--verbose", verbose, "Log debug messages");
  app.parse_complete_callback(
      [&] { spdlog::set_level(verbose ? spdlog::level::debug : spdlog::level::info); });

  conicloc::tools::add_evaluate_command(app);
  conicloc::tools::add_predict_command(app);
  conicloc::tools::add_map_info_command(app);
  conicloc::tools::add_map_export_command(app);
  conicloc::tools::add_decode_command(app);
  conicloc::tools::add_simulate_command(app);
  conicloc::tools::add_localize_command(app);
  conicloc::tools::add_replay_command(app);
  conicloc::tools::add_report_command(app);
  conicloc::tools::add_generate_building_command(app);
  conicloc::tools::add_calibrate_command(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  return 0;
}
