#pragma once
// Returns put back in azimuth order after de-skew moved each by a fraction of a degree: a
// general O(n log n) sort of the ~29,000 returns of a VLP-16 scan, every scan, spent some 5 % of
// tracking's time re-sorting what was nearly sorted.

#include <vector>

#include "sensor/scan.hpp"

namespace conicloc::sensor {

/// Sorts `returns` by azimuth, stably (equal azimuths keep their order): exactly the order
/// std::stable_sort gives. O(n) for a ring in ascending order but for returns a few places out
/// and wraps (the azimuth dropping by more than π where de-skew carried returns across 2π → 0);
/// O(n log n) for any other order (a ring in firing order descends: the sensor spins clockwise).
/// Azimuths must be numbers: a NaN is ordered nowhere, by this as by std::stable_sort.
void sort_by_azimuth(std::vector<Return>& returns);

}  // namespace conicloc::sensor
