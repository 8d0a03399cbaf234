#pragma once
// The point CSV written by `conicloc decode --csv` and `conicloc predict --csv`: one interface,
// scripted against, so both commands take the column list from here.

namespace conicloc::tools {

inline constexpr const char* kPointCsvHeader =
    "scan,ring,azimuth_deg,range_m,intensity,time_s,x,y,z,return\n";

}  // namespace conicloc::tools
