#pragma once
// `localize --report-dir DIR`: writes, while localizing, what `conicloc report` draws. The folder:
//   poses.tum     the estimate of every scan (TUM, UTC), as `localize --out`
//   details.csv   every scan's diagnostics, as `localize --details` (tools/details_csv.hpp)
//   frames.jsonl  every `frame_every`-th scan: one JSON frame a line (tools/report_frame_json.hpp)
//   run.json      written at the end: the run's summary, the rings and the sampling (see finish())
// A 10-minute run at 10 Hz with the default frame_every = 10 holds 600 frames of ~20 kB.

#include <filesystem>
#include <fstream>
#include <string>

#include "eval/report_frame.hpp"
#include "localizer/conic/conic_scan_predictor.hpp"
#include "run/localize_run.hpp"

namespace conicloc::tools {

struct ReportRecorderConfig {
  std::size_t frame_every = 10;  ///< a frame every this many scans (the first scan always)
  eval::ReportFrameLimits limits;
};

/// What run.json says of the run besides the recorder's own counts.
struct ReportRunInfo {
  std::string capture;  ///< the capture's path
  std::string model;    ///< observation model
  bool global = false;  ///< global start
};

class ReportRecorder {
 public:
  /// Creates `dir` (and parents); throws io::InputError when a file in it cannot be written.
  /// Keeps a reference to `map`, which must outlive the recorder.
  ReportRecorder(const std::filesystem::path& dir, const maps::PlaneMap& map,
                 const sensor::LaserCalibration& calibration, ReportRecorderConfig config = {});

  void record(double utc_s, const localizer::UpdateResult& result, const run::ScanState& state);

  /// Writes run.json (run_json()).
  void finish(const run::LocalizeRunSummary& summary, const ReportRunInfo& info);

  std::size_t frames() const { return frames_; }

 private:
  std::filesystem::path dir_;
  ReportRecorderConfig config_;
  localizer::ConicScanPredictor predictor_;
  std::ofstream poses_, details_, frames_out_;
  std::size_t scans_ = 0;
  std::size_t frames_ = 0;
};

/// The run's summary for the report, one JSON object: {"capture", "model", "global", "scans",
/// "skipped_partial", "recoveries", "mean_time_ms", "p95_time_ms", "max_time_ms",
/// "realtime_factor", "point_clouds", "packets": {"decoded", "rejected", "lost"}, "frame_every",
/// "frames", "conic_step_deg",
/// "max_particles", "points_per_ring", "rings": [[elevation_deg, vertical_offset_m], …]}
/// (rings indexed by ring, lowest elevation first).
std::string run_json(const run::LocalizeRunSummary& summary, const ReportRunInfo& info,
                     const ReportRecorderConfig& config, std::size_t frames,
                     const std::vector<localizer::RingGeometry>& rings);

}  // namespace conicloc::tools
