#include "tools/report_recorder.hpp"

#include <numbers>
#include <sstream>

#include "io/input_error.hpp"
#include "io/tum_trajectory.hpp"
#include "tools/details_csv.hpp"
#include "tools/json_writer.hpp"
#include "tools/report_frame_json.hpp"

namespace conicloc::tools {

namespace {

/// Opens `path` for writing or throws io::InputError naming it.
std::ofstream open_for_writing(const std::filesystem::path& path) {
  std::ofstream out(path);
  if (!out) throw io::InputError(path.string(), "", "cannot open for writing");
  return out;
}

}  // namespace

ReportRecorder::ReportRecorder(const std::filesystem::path& dir, const maps::PlaneMap& map,
                               const sensor::LaserCalibration& calibration,
                               ReportRecorderConfig config)
    : dir_(dir), config_(config), predictor_(map, calibration) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) throw io::InputError(dir.string(), "", "cannot create folder: " + error.message());
  poses_ = open_for_writing(dir / "poses.tum");
  details_ = open_for_writing(dir / "details.csv");
  frames_out_ = open_for_writing(dir / "frames.jsonl");
  details_ << details_header() << "\n";
}

void ReportRecorder::record(double utc_s, const localizer::UpdateResult& result,
                            const run::ScanState& state) {
  io::write_tum_line(poses_, {utc_s, result.pose});
  details_ << details_row(utc_s, result);
  if (scans_ % std::max<std::size_t>(config_.frame_every, 1) == 0) {
    const auto frame = eval::make_report_frame(utc_s, scans_, result.pose, state.scan,
                                               &state.particles, predictor_, config_.limits);
    frames_out_ << report_frame_json(frame) << "\n";
    ++frames_;
  }
  ++scans_;
}

void ReportRecorder::finish(const run::LocalizeRunSummary& summary, const ReportRunInfo& info) {
  poses_.flush();
  details_.flush();
  frames_out_.flush();
  if (!poses_ || !details_ || !frames_out_)
    throw io::InputError(dir_.string(), "", "writing the report files failed");
  std::ofstream out = open_for_writing(dir_ / "run.json");
  out << run_json(summary, info, config_, frames_, predictor_.rings()) << "\n";
  if (!out) throw io::InputError((dir_ / "run.json").string(), "", "writing failed");
}

std::string run_json(const run::LocalizeRunSummary& summary, const ReportRunInfo& info,
                     const ReportRecorderConfig& config, std::size_t frames,
                     const std::vector<localizer::RingGeometry>& rings) {
  constexpr double kRadToDeg = 180.0 / std::numbers::pi;
  std::ostringstream out;
  JsonWriter json(out);
  json.begin_object();
  json.key("capture").value(info.capture);
  json.key("model").value(info.model);
  json.key("global").value(info.global);
  json.key("scans").value(summary.scans);
  json.key("skipped_partial").value(summary.skipped_partial);
  json.key("recoveries").value(summary.recoveries);
  json.key("mean_time_ms").value(summary.mean_time_ms());
  json.key("p95_time_ms").value(summary.quantile_time_ms(0.95));
  json.key("max_time_ms").value(summary.max_time_ms());
  json.key("realtime_factor").value(summary.realtime_factor());
  json.key("point_clouds").value(summary.point_clouds);
  json.key("packets").begin_object();
  json.key("decoded").value(summary.stream.data_packets);
  json.key("rejected").value(summary.stream.rejected_total());
  json.key("lost").value(summary.stream.packets_lost);
  json.end_object();
  json.key("frame_every").value(config.frame_every);
  json.key("frames").value(frames);
  json.key("conic_step_deg").value(config.limits.conic_step_rad * kRadToDeg);
  json.key("max_particles").value(config.limits.max_particles);
  json.key("points_per_ring").value(config.limits.points_per_ring);
  json.key("rings").begin_array();
  for (const auto& ring : rings) {
    json.begin_array();
    json.value(ring.elevation_rad * kRadToDeg);
    json.value(ring.vertical_offset_m);
    json.end_array();
  }
  json.end_array();
  json.end_object();
  return out.str();
}

}  // namespace conicloc::tools
