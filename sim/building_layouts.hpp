#pragma once
// The layouts of the generated buildings, every dimension, count and position drawn from `rng`
// (portable draws, sim/seeded_draw.hpp). Each returns a whole building: cells, doors joining every
// cell to the rest, and summary lines saying what was drawn.

#include <random>

#include "sim/building_generator.hpp"
#include "sim/prism_building.hpp"

namespace conicloc::sim {

/// One storey: a corridor (20–40 m × 2–3 m) with 4–8 rooms on both sides, one room under a
/// sloped ceiling (12–20°), the east facade slanted 10–35° off north (non-Manhattan).
PrismBuilding corridor_layout(std::mt19937_64& rng);

/// A lobby between two mirror-image wings (a corridor with 2–4 rooms on each side): the same
/// view at mirrored poses, on purpose. One room of the east wing has a sloped ceiling.
PrismBuilding wings_layout(std::mt19937_64& rng);

/// A hall (15–30 m per side, 4–6 m high) with a grid of square pillars (interior shells of the
/// hall's solid) and 2–4 rooms along its south wall; the hall's State stands in the pillar-free
/// aisle along that wall, so routes through the hall keep clear of the pillars.
PrismBuilding hall_layout(std::mt19937_64& rng);

/// 2–4 identical storeys (corridor, rooms on both sides) joined by straight stairs, one per
/// storey pair (a TransitionSpace with landing, flight and landing), alternating between two
/// stairwell lanes north of the corridor. `scale` fixes the storey count instead of drawing it and
/// repeats the floor plate (the rooms along one stretch of corridor, drawn anew per plate) along
/// a corridor that many times longer; the default scale gives the seed's building.
PrismBuilding storeys_layout(std::mt19937_64& rng, const BuildingScale& scale = {});

}  // namespace conicloc::sim
