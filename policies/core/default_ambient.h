#pragma once
// What a planner answers where it holds no data at all (a cold start before its first probe is
// delivered, or a point its structure cannot serve): the default ambient an engine ships with,
// a sky above and a ground below, the `hemisphere` baseline's artist default. Black would be
// the one answer that is always wrong: at budget 0 it scored 35.6 dE00 mean against
// `constant`'s 6.9 (docs/STABILITY.md).
#include "sim/colour/rgb.h"
#include "sim/planner.h"
#include "sim/sh/sh9.h"

namespace ambisim {

// Default radiances of the two hemispheres (linear, the sky's zenith is O(1)).
inline constexpr float kDefaultSkyRadiance = 1.0f;
inline constexpr float kDefaultGroundRadiance = 0.25f;

// The SH9 projection of radiance `sky` from every direction with z > 0 and `ground` below:
// L00 = sqrt(pi) (sky + ground), L10 = pi Y1 (sky - ground), every other term 0 (exact).
Sh9Rgb hemisphere_sh(const Rgb& sky, const Rgb& ground);

// hemisphere_sh of the default radiances.
const Sh9Rgb& default_ambient_sh();

// A lookup served by nothing: the default ambient, fell_back, no contributors, infinite spacing.
LookupResult default_ambient_lookup();

}  // namespace ambisim
