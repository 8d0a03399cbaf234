#include "localizer/models/beam_selection.hpp"

#include <algorithm>

namespace conicloc::localizer {

namespace {
bool usable(const sensor::Return& ret, const BeamSelectionConfig& config, double max_range_m) {
  return ret.status == sensor::ReturnStatus::Valid && ret.range_m >= config.min_range_m &&
         ret.range_m <= max_range_m;
}
}  // namespace

std::vector<std::vector<SelectedBeam>> select_beams(const sensor::Scan& scan,
                                                    const BeamSelectionConfig& config,
                                                    double max_range_m) {
  std::size_t usable_count = 0;
  for (const auto& ring : scan.rings) {
    for (const auto& ret : ring.returns) usable_count += usable(ret, config, max_range_m) ? 1 : 0;
  }
  // The stride as a real number so the kept count is close to max_beams, not halved.
  const double stride = config.max_beams == 0 || usable_count <= config.max_beams
                            ? 1.0
                            : static_cast<double>(usable_count) / config.max_beams;
  std::vector<std::vector<SelectedBeam>> selected(scan.rings.size());
  double next = 0.0;
  std::size_t seen = 0;
  for (std::size_t r = 0; r < scan.rings.size(); ++r) {
    for (const auto& ret : scan.rings[r].returns) {
      if (!usable(ret, config, max_range_m)) continue;
      if (static_cast<double>(seen++) >= next) {
        selected[r].push_back({static_cast<int>(r), ret.azimuth_rad, ret.range_m});
        next += stride;
      }
    }
    std::sort(
        selected[r].begin(), selected[r].end(),
        [](const SelectedBeam& a, const SelectedBeam& b) { return a.azimuth_rad < b.azimuth_rad; });
  }
  return selected;
}

}  // namespace conicloc::localizer
