#pragma once
// Linear HDR colour. Radiance and irradiance are stored as float RGB: seven significant digits
// are far beyond what a display or the metrics resolve, and half the memory of double.
#include <glm/vec3.hpp>

namespace ambisim {
using Rgb = glm::vec3;
}  // namespace ambisim
