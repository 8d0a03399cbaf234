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
  sensor::Scan out = scan;
  for (std::size_t k = 0; k < out.rings.size(); ++k) {
    if (!std::binary_search(rings.begin(), rings.end(), static_cast<int>(k))) {
      out.rings[k].returns.clear();
    }
  }
  return out;
}

}  // namespace conicloc::localizer
