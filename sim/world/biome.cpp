#include "sim/world/biome.h"

namespace ambisim {

std::string_view biome_name(Biome b) {
  switch (b) {
    case Biome::Grass:
      return "grass";
    case Biome::Forest:
      return "forest";
    case Biome::Rock:
      return "rock";
    case Biome::Water:
      return "water";
    case Biome::Field:
      return "field";
    case Biome::Sand:
      return "sand";
    case Biome::Snow:
      return "snow";
    case Biome::Asphalt:
      return "asphalt";
    case Biome::Count:
      break;
  }
  return "?";
}

Rgb biome_albedo(Biome b) {
  // Linear values; e.g. grass 0.10/0.32/0.05 is a saturated lawn green in sRGB.
  switch (b) {
    case Biome::Grass:
      return {0.10f, 0.32f, 0.05f};
    case Biome::Forest:
      return {0.03f, 0.11f, 0.03f};
    case Biome::Rock:
      return {0.30f, 0.25f, 0.20f};
    case Biome::Water:
      return {0.02f, 0.05f, 0.16f};
    case Biome::Field:
      return {0.60f, 0.45f, 0.08f};
    case Biome::Sand:
      return {0.65f, 0.55f, 0.35f};
    case Biome::Snow:
      return {0.85f, 0.87f, 0.90f};
    case Biome::Asphalt:
      return {0.07f, 0.07f, 0.075f};
    case Biome::Count:
      break;
  }
  return {0.0f, 0.0f, 0.0f};
}

}  // namespace ambisim
