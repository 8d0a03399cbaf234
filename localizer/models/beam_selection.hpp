#pragma once
// Beam subsampling shared by the observation models: a deterministic, evenly spread subset of
// the valid returns of a scan, so a model's cost does not grow with the sensor's resolution.

#include <cstddef>
#include <vector>

#include "sensor/scan.hpp"

namespace conicloc::localizer {

struct BeamSelectionConfig {
  std::size_t max_beams = 2000;  ///< upper bound on the returns kept per scan; 0 keeps all
  double min_range_m = 0.5;      ///< closer returns (the carrier, the operator) are dropped
};

/// One selected return.
struct SelectedBeam {
  int ring = 0;  ///< index into Scan::rings
  double azimuth_rad = 0.0;
  double range_m = 0.0;
};

/// The selected returns per ring, each ring sorted by azimuth; rings with nothing are empty.
/// Every ring keeps the same stride, so the subset stays spread over all rings and azimuths.
/// Returns beyond `max_range_m` (the sensor's maximum range) are not selected.
std::vector<std::vector<SelectedBeam>> select_beams(const sensor::Scan& scan,
                                                    const BeamSelectionConfig& config,
                                                    double max_range_m);

}  // namespace conicloc::localizer
