#pragma once
// Surface classes of the world and their albedos. The albedos are deliberately saturated
// (thesis: blue sky, green forest, golden sand bunkers) so colour pops are measurable.
#include <array>
#include <cstdint>
#include <string_view>

#include "sim/colour/rgb.h"

namespace ambisim {

enum class Biome : std::uint8_t {
  Grass = 0,
  Forest,   // canopy layer 15-25 m above the ground
  Rock,     // steep slopes, cliffs, road cuttings
  Water,    // flat lakes at the water level
  Field,    // yellow/gold crop parcels
  Sand,     // beaches and bunkers
  Snow,     // peaks above the snow line
  Asphalt,  // the motorway
  Count
};
inline constexpr int kBiomeCount = static_cast<int>(Biome::Count);

std::string_view biome_name(Biome b);

// Linear-RGB diffuse albedo in [0, 1] per channel.
Rgb biome_albedo(Biome b);

// Albedo of the flat "far ground" beyond the grid: a neutral grey.
inline constexpr float kFarGroundAlbedo = 0.25f;

}  // namespace ambisim
