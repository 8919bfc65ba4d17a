#pragma once
// Accuracy of a planner's irradiance against the reference (SPEC section 5), per receiver,
// normal and frame:
// - relative error  ||P - R||_2 / max(||R||_2, floor), the Euclidean norm over linear RGB;
//   the floor keeps a black reference from dividing by 0 (the error is then absolute, in
//   units of the floor);
// - perceptual error  ciede2000(display_lab(P, x), display_lab(R, x)): both colours through the
//   same fixed exposure x and global tone map, so the number is what a viewer would see.
// The exposure is fixed per scenario and comes from the reference only (reference_exposure),
// never from a planner: a planner-derived exposure would let a planner move its own yardstick.
#include <span>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "sim/colour/cielab.h"
#include "sim/colour/rgb.h"

namespace ambisim {

// Relative error as above. p, r: linear HDR irradiance (any finite values); floor > 0.
double relative_error(const Rgb& p, const Rgb& r, double floor);

// CIEDE2000 between the displayed colours of two linear irradiances; exposure > 0.
double display_difference(const Rgb& p, const Rgb& r, double exposure);
// The same when the Lab colours are already known (the metrics compute them once per frame).
double display_difference(const Lab& p, const Lab& r);

// Exposure from reference irradiances: Reinhard's key / log-average luminance (seed 003 eq. 3.2),
// over every reference sample of the scenario (all receivers, normals, frames). key in (0, 1];
// an empty or all-black reference gives the exposure of the log-average's delta (finite).
double reference_exposure(std::span<const Rgb> reference_irradiance, double key);

// The fixed sets of normals accuracy and pops are evaluated over (unit vectors, z up):
// "axes6"  = +-x, +-y, +-z (a cube's face normals: what an axis-aligned ambient cube stores);
// "axes26" = the 26 directions from a cube's centre to its face centres, edge midpoints and
//            corners, normalised (adds the diagonals, where L2 ringing and sky/ground mixing show).
// Order: axes6 is +x, -x, +y, -y, +z, -z; axes26 enumerates (i, j, k) in {-1, 0, 1}^3 with i
// slowest, skipping (0, 0, 0). Throws std::invalid_argument for another name.
std::vector<glm::dvec3> normal_set(std::string_view name);

}  // namespace ambisim
