// `conicloc report --report-dir DIR --out run.html`: one self-contained HTML page of a
// localization run (tools/report_page.hpp), from the folder `localize --report-dir` wrote, or from
// the explicit inputs (--pcap --estimate --details), where the frames are re-drawn from the
// capture at the estimates and the particles, which only the filter had, are left out.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "eval/details_csv_reader.hpp"
#include "io/input_error.hpp"
#include "io/scan_source.hpp"
#include "io/tum_trajectory.hpp"
#include "sensor/builtin_calibration.hpp"
#include "tools/commands.hpp"
#include "tools/map_options.hpp"
#include "tools/report_frame_json.hpp"
#include "tools/report_page.hpp"
#include "tools/report_recorder.hpp"

namespace conicloc::tools {
namespace {

struct ReportOptions {
  std::string map_path = example_map_path();
  io::MapLoadOptions map_options;
  std::string report_dir;
  std::string pcap_path;
  std::string topic;
  std::string estimate_path;
  std::string details_path;
  std::string truth_path;
  std::string sensor_model = "vlp16";
  std::size_t frame_every = 10;
  std::size_t max_frames = 600;
  std::string out_path;
};

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw io::InputError(path.string(), "", "cannot open");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The frames of frames.jsonl, one JSON object a line (tools/report_frame_json.hpp). Checked for
/// shape only (an object with a time first) so that a cut or foreign file is named, not embedded.
std::vector<std::string> read_frames(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw io::InputError(path.string(), "", "cannot open");
  std::vector<std::string> frames;
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    if (line.rfind("{\"t\":", 0) != 0 || line.back() != '}') {
      throw io::InputError(path.string(), "line " + std::to_string(number),
                           "not a report frame (a JSON object starting with \"t\")");
    }
    frames.push_back(std::move(line));
  }
  return frames;
}

/// The summary of a run known only by its details and its capture's stream.
run::LocalizeRunSummary summary_of(const std::vector<eval::DetailsRow>& details) {
  run::LocalizeRunSummary summary;
  summary.scans = details.size();
  for (const auto& row : details) {
    summary.scan_times_ms.push_back(row.time_ms);
    summary.recoveries += row.recovered ? 1 : 0;
  }
  if (!details.empty()) {
    summary.first_time_s = details.front().time_s;
    summary.last_time_s = details.back().time_s;
  }
  return summary;
}

/// Explicit inputs: the capture's scans at the estimates, every `frame_every`-th estimated scan.
void redraw_frames(const ReportOptions& o, const maps::PlaneMap& map,
                   const std::vector<io::StampedPose>& estimate, ReportPageInputs& inputs) {
  const auto model = sensor::parse_sensor_model(o.sensor_model);
  if (!model)
    throw CLI::ValidationError("--sensor-model", "unknown sensor model '" + o.sensor_model + "'");
  const auto calibration = sensor::builtin_calibration(*model);
  io::ScanSourceOptions source_options;
  source_options.capture.topic = o.topic;
  const auto source = io::open_scan_source(o.pcap_path, calibration, source_options);
  const localizer::ConicScanPredictor predictor(map, calibration);
  // A scan belongs to the estimate stamped with its end (UTC; written with µs precision).
  constexpr double kMatchTolerance_s = 1e-3;
  std::size_t matched = 0;
  std::size_t frames = 0;
  while (const auto scan = source->next()) {
    const double utc_s = scan->end_time_s + source->utc_offset_s().value_or(0.0);
    const auto at =
        std::lower_bound(estimate.begin(), estimate.end(), utc_s - kMatchTolerance_s,
                         [](const io::StampedPose& p, double t) { return p.time_s < t; });
    if (at == estimate.end() || at->time_s > utc_s + kMatchTolerance_s) continue;
    const auto index = static_cast<std::size_t>(at - estimate.begin());
    if (matched++ % o.frame_every == 0) {
      const auto frame = eval::make_report_frame(utc_s, index, at->pose, *scan, nullptr, predictor);
      inputs.frames.push_back(report_frame_json(frame));
      ++frames;
    }
  }
  spdlog::info("{}: {} of {} estimates matched a scan", o.pcap_path, matched, estimate.size());
  if (matched == 0) {
    throw io::InputError(o.pcap_path, "",
                         "no scan ends at a time of " + o.estimate_path +
                             " (is it the capture that was localized?)");
  }
  run::LocalizeRunSummary summary = summary_of(inputs.details);
  if (const io::VelodyneStream* stream = source->stream()) {
    summary.stream = stream->stats();
  } else {
    summary.point_clouds = true;
  }
  inputs.frame_every = o.frame_every;
  inputs.particles_recorded = false;
  inputs.run_json =
      run_json(summary, {.capture = o.pcap_path, .model = "", .global = false},
               {.frame_every = o.frame_every, .limits = {}}, frames, predictor.rings());
}

/// frame_every of a run.json: the one unsigned number after its key.
std::size_t frame_every_of(const std::string& run, const std::string& file) {
  const std::string key = "\"frame_every\":";
  const std::size_t at = run.find(key);
  if (at == std::string::npos) throw io::InputError(file, "", "no \"frame_every\"");
  try {
    return std::stoul(run.substr(at + key.size()));
  } catch (const std::exception&) {
    throw io::InputError(file, "\"frame_every\"", "not a number");
  }
}

void run_report(const ReportOptions& o) {
  const maps::PlaneMap map = load_map(o.map_path, o.map_options).map;
  ReportPageInputs inputs;
  if (!o.report_dir.empty()) {
    const std::filesystem::path dir = o.report_dir;
    inputs.title = dir.filename().string();
    inputs.details =
        eval::read_details_csv(read_text(dir / "details.csv"), (dir / "details.csv").string());
    inputs.frames = read_frames(dir / "frames.jsonl");
    std::string run = read_text(dir / "run.json");
    while (!run.empty() && std::isspace(static_cast<unsigned char>(run.back()))) run.pop_back();
    if (run.empty() || run.front() != '{' || run.back() != '}')
      throw io::InputError((dir / "run.json").string(), "", "not a JSON object");
    inputs.frame_every = frame_every_of(run, (dir / "run.json").string());
    inputs.run_json = std::move(run);
  } else {
    if (o.pcap_path.empty() || o.estimate_path.empty() || o.details_path.empty()) {
      throw CLI::ValidationError("report",
                                 "give --report-dir, or --pcap, --estimate and --details");
    }
    inputs.title = std::filesystem::path(o.estimate_path).stem().string();
    inputs.details = eval::read_details_csv(read_text(o.details_path), o.details_path);
    redraw_frames(o, map, io::read_tum(o.estimate_path), inputs);
  }
  if (inputs.details.empty()) throw CLI::ValidationError("report", "the run has no localized scan");
  if (!o.truth_path.empty()) inputs.truth = io::read_tum(o.truth_path);

  const ReportPage page = make_report_page(map, inputs, {.max_frames = o.max_frames});
  std::ofstream out(o.out_path, std::ios::binary);
  if (!out) throw io::InputError(o.out_path, "", "cannot open for writing");
  out << page.html;
  out.close();
  if (!out) throw io::InputError(o.out_path, "", "write failed");
  const std::size_t scans = inputs.details.size();
  spdlog::info("sampled: a frame every {} scans ({} of {} scans); {} scans in the plots",
               inputs.frame_every * page.frame_stride, page.frames_embedded, scans,
               (scans + page.series_stride - 1) / page.series_stride);
  spdlog::info("report written to {} ({:.2f} MB); open it in a browser: file://{}", o.out_path,
               static_cast<double>(page.html.size()) / 1e6,
               std::filesystem::absolute(o.out_path).string());
}

}  // namespace

void add_report_command(CLI::App& app) {
  auto options = std::make_shared<ReportOptions>();
  auto* cmd = app.add_subcommand(
      "report",
      "Write one self-contained HTML page of a localization run (opens from disk, no network):\n"
      "floor plans with the estimated and true trajectories, a time slider over sampled frames\n"
      "(particles, measured returns, conics predicted at the estimate; plan and 3D views), the\n"
      "per-scan plots and the run's summary. Input: the folder of `localize --report-dir`, or\n"
      "--pcap --estimate --details (frames re-drawn from the capture, without particles).");
  cmd->add_option("--map", options->map_path, "IndoorGML map the run was localized in")
      ->check(CLI::ExistingFile);
  add_map_load_options(cmd, options->map_options);
  cmd->add_option("--report-dir", options->report_dir, "Folder written by `localize --report-dir`")
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--pcap,--capture", options->pcap_path, "Capture that was localized")
      ->check(CLI::ExistingPath);
  cmd->add_option("--topic", options->topic, "Bag topic of the capture (default: the only one)");
  cmd->add_option("--estimate", options->estimate_path, "`localize --out` trajectory (TUM)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--details", options->details_path, "`localize --details` CSV")
      ->check(CLI::ExistingFile);
  cmd->add_option("--sensor-model", options->sensor_model,
                  "With --pcap: vlp16, puck-lite, puck-hires, hdl32e, vlp32c")
      ->capture_default_str();
  cmd->add_option("--report-every", options->frame_every,
                  "With --pcap: a frame every this many localized scans")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--truth", options->truth_path, "Ground truth (TUM, UTC): errors and accuracy")
      ->check(CLI::ExistingFile);
  cmd->add_option("--max-frames", options->max_frames,
                  "Frames embedded at most (an even subsample; the page says so)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--out", options->out_path, "Output HTML page")->required();
  cmd->callback([options] { run_report(*options); });
}

}  // namespace conicloc::tools
