#include "calib/truth_comparison.hpp"

#include <cmath>
#include <stdexcept>

namespace conicloc::calib {
namespace {

// RMS of the values, about their mean when `centred`.
double rms(const std::vector<double>& values, bool centred) {
  if (values.empty()) return 0.0;
  double mean = 0.0;
  for (const double v : values) mean += v / static_cast<double>(values.size());
  if (!centred) mean = 0.0;
  double sum = 0.0;
  for (const double v : values) sum += (v - mean) * (v - mean);
  return std::sqrt(sum / static_cast<double>(values.size()));
}

}  // namespace

TruthErrors compare_to_truth(const CalibrationResult& result,
                             const sensor::LaserCalibration& decode,
                             const sensor::LaserCalibration& truth) {
  if (truth.lasers.size() != decode.lasers.size() || result.lasers.size() != decode.lasers.size()) {
    throw std::invalid_argument("compare_to_truth: the truth has " +
                                std::to_string(truth.lasers.size()) + " lasers, the estimate " +
                                std::to_string(result.lasers.size()));
  }
  std::array<std::vector<double>, 4> errors;
  TruthErrors out;
  for (std::size_t k = 0; k < truth.lasers.size(); ++k) {
    const LaserEstimate& estimate = result.lasers[k];
    const sensor::Laser& d = decode.lasers[k];
    const sensor::Laser& t = truth.lasers[k];
    const std::array<double, 4> error = {
        d.elevation_rad + estimate.correction.elevation_rad - t.elevation_rad,
        d.vertical_offset_m + estimate.correction.vertical_offset_m - t.vertical_offset_m,
        d.azimuth_offset_rad + estimate.correction.azimuth_rad - t.azimuth_offset_rad,
        d.range_offset_m + estimate.correction.range_m - t.range_offset_m};
    for (int i = 0; i < 4; ++i) {
      if (estimate.observability.observable[i]) {
        errors[i].push_back(error[i]);
        ++out.compared[i];
      } else {
        ++out.unobservable[i];
      }
    }
  }
  out.elevation_rms_rad = rms(errors[0], false);
  out.vertical_offset_rms_m = rms(errors[1], true);
  out.azimuth_rms_rad = rms(errors[2], true);
  out.range_offset_rms_m = rms(errors[3], false);
  return out;
}

}  // namespace conicloc::calib
