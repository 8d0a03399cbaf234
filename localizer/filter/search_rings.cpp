#include "localizer/filter/search_rings.hpp"

#include <algorithm>
#include <numeric>

namespace conicloc::localizer {

std::vector<int> spread_rings(std::size_t ring_count, std::size_t count) {
  std::vector<int> rings;
  if (count == 0 || count >= ring_count) {
    rings.resize(ring_count);
    std::iota(rings.begin(), rings.end(), 0);
    return rings;
  }
  for (std::size_t i = 0; i < count; ++i) {
    rings.push_back(static_cast<int>((2 * i + 1) * ring_count / (2 * count)));
  }
  return rings;
}

sensor::Scan keep_rings(const sensor::Scan& scan, std::span<const int> rings) {
  sensor::Scan out;
  out.index = scan.index;
  out.start_time_s = scan.start_time_s;
  out.end_time_s = scan.end_time_s;
  out.partial = scan.partial;
  out.rings.resize(scan.rings.size());
  for (std::size_t k = 0; k < scan.rings.size(); ++k) {
    const sensor::RingScan& ring = scan.rings[k];
    sensor::RingScan& kept = out.rings[k];
    kept.ring = ring.ring;
    kept.channel = ring.channel;
    kept.elevation_rad = ring.elevation_rad;
    kept.vertical_offset_m = ring.vertical_offset_m;
    if (std::binary_search(rings.begin(), rings.end(), static_cast<int>(k))) {
      kept.returns = ring.returns;
    }
  }
  return out;
}

}  // namespace conicloc::localizer
