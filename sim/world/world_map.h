#pragma once
// Top-down colour map of a world for reports and views: albedo x hillshade x sun shadow,
// road centre line drawn, north up (row 0 is the northern edge), sRGB-encoded.
#include "sim/base/image.h"
#include "sim/world/world.h"

namespace ambisim {

// The longer side gets max_size_px pixels (>= 1); each pixel samples the cell at its centre.
ImageRgb8 world_map_image(const World& w, int max_size_px);

}  // namespace ambisim
