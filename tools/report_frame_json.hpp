#pragma once
// A sampled frame (eval/report_frame.hpp) as one line of JSON, rounded to what a page can show
// (cm, 0.1°) to keep an hour's run small. The format of `localize --report-dir`'s frames.jsonl:
//   {"t": UTC s, "scan": index of the localized scan,
//    "T": T_map_sensor row-major 3×4 (r00 r01 r02 tx r10 … tz),
//    "n": particles in the cloud, "particles": [x, y, z, yaw_rad, …] (an even subsample; the key is
//    absent when the particles were not recorded),
//    "measured": per ring [azimuth_deg, range_m, …], "predicted": per ring [range_m, …] at
//    azimuths 0, step, 2·step, … (run.json's conic_step_deg; 0: no return)}

#include <fmt/format.h>

#include <string>

#include "eval/report_frame.hpp"

namespace conicloc::tools {

/// `value` with `decimals` decimals, trailing zeros dropped ("12.3", not "12.300"; "0", not
/// "-0.00"); null when not finite.
void append_fixed(fmt::memory_buffer& out, double value, int decimals);

/// The frame as one JSON object, without a newline.
std::string report_frame_json(const eval::ReportFrame& frame);

}  // namespace conicloc::tools
