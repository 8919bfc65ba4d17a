#pragma once
// Linear HDR colour. Radiance and irradiance are stored as float RGB: seven significant digits
// are far beyond what a display or the metrics resolve, and half the memory of double.
#include <glm/vec3.hpp>

namespace ambisim {
using Rgb = glm::vec3;

// Relative luminance Y of linear sRGB (Rec. 709 primaries), in double.
inline double luminance(const Rgb& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }
}  // namespace ambisim
