#pragma once
// A searching cloud scores a few rings. A prediction costs a fixed part plus one part per ring
// (10 × 4 generated storeys, every polygon a candidate: 35 µs with no ring, 325 µs with 16, 124
// µs with 4), and a cloud that searches the building after a global start or a recovery predicts
// one pose per particle: 5,000 full predictions made its first two scans cost a second each.
// While it searches, the scan's likelihood is tempered to keep half the cloud anyway
// (adaptive_tempering.hpp), so the rings beyond a few spread over the elevations (the floor, the
// walls far and near, the ceiling) sharpen little that the search keeps; once the cloud holds one
// place, every ring is scored again.

#include <cstddef>
#include <span>
#include <vector>

#include "sensor/scan.hpp"

namespace conicloc::localizer {

/// `count` of `ring_count` rings (indices by elevation rank), one from the middle of each of
/// `count` equal bands of elevation rank: ⌊(i + ½) · ring_count / count⌋ for i < count
/// (16 rings, 4: 2, 6, 10, 14). Every ring when count is 0 or at least ring_count.
std::vector<int> spread_rings(std::size_t ring_count, std::size_t count);

/// `scan` with the returns of only the rings listed in `rings` (ascending); the other rings are
/// kept, empty.
sensor::Scan keep_rings(const sensor::Scan& scan, std::span<const int> rings);

}  // namespace conicloc::localizer
