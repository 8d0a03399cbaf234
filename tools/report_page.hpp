#pragma once
// The page of `conicloc report`: one self-contained HTML file (inline CSS and JavaScript, the data
// as JSON in a <script type="application/json"> element, no URL anywhere) drawing a localization
// run: the floor plan of each storey with the estimated and true trajectories, a time slider over
// the sampled frames (particles, measured returns and the conics predicted at the estimate, in a
// plan view and a 3D view), the per-scan plots and the run's summary. The page's script is
// tools/report_page.html, embedded at build time.

#include <string>
#include <vector>

#include "eval/details_csv_reader.hpp"
#include "io/tum_trajectory.hpp"
#include "maps/plane_map.hpp"

namespace conicloc::tools {

struct ReportPageInputs {
  std::string title;
  /// The run's summary: run.json of `localize --report-dir` (tools/report_recorder.hpp), or an
  /// object of the same keys made from the explicit inputs. Must hold "rings" and
  /// "conic_step_deg".
  std::string run_json;
  /// Frames in time order, one JSON object each (tools/report_frame_json.hpp), recorded every
  /// `frame_every`-th scan.
  std::vector<std::string> frames;
  std::size_t frame_every = 1;
  bool particles_recorded = true;
  std::vector<eval::DetailsRow> details;  ///< every localized scan
  std::vector<io::StampedPose> truth;     ///< empty: no truth, no errors
};

struct ReportPageLimits {
  std::size_t max_frames = 600;     ///< frames embedded (an even subsample)
  std::size_t max_series = 20000;   ///< per-scan samples embedded (an even subsample)
  std::size_t max_polygons = 5000;  ///< map polygons in the 3D view (the largest)
};

struct ReportPage {
  std::string html;
  std::size_t frames_embedded = 0;
  std::size_t frame_stride = 1;   ///< every frame_stride-th recorded frame embedded
  std::size_t series_stride = 1;  ///< every series_stride-th scan in the plots
};

/// The page. Its own size in bytes is written into it (the data's "page_bytes").
ReportPage make_report_page(const maps::PlaneMap& map, const ReportPageInputs& inputs,
                            const ReportPageLimits& limits = {});

/// `text` made safe inside a <script> element: every '<' becomes the JSON escape \u003c (valid in
/// JSON strings; JSON outside strings has no '<').
std::string script_safe_json(const std::string& text);

}  // namespace conicloc::tools
