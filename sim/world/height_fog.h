#pragma once
// Exponential height fog, the games' standard (seed 004 section 2.3 gives the attenuation
// f = exp(-integral of sigma along the ray), eq. 2.2's blend C = f C_in + (1 - f) C_fog; Unreal's
// exponential height fog uses this density): sigma(z) = density exp(-(z - base) / falloff), plus
// an optional homogeneous extinction. The optical depth along a ray has a closed form:
//   tau(o, d, t) = density falloff exp(-(o.z - base) / falloff) (1 - exp(-d.z t / falloff)) / d.z
// (and density exp(-(o.z - base) / falloff) t as d.z -> 0). Density and base change over time by
// linear interpolation of keys (a bank rising from a lake).
#include <vector>

#include <glm/vec3.hpp>

#include "sim/world/lighting_params.h"

namespace ambisim {

struct FogState {
  double homogeneous_per_m = 0.0;
  bool height = false;
  double density_per_m = 0.0;
  double base_m = 0.0;
  double falloff_m = 15.0;

  // Optical depth from o along unit d over t metres (t = +inf: an escaping ray; only the
  // height fog above stays finite for d.z > 0, and the homogeneous part is not applied to it).
  double optical_depth(const glm::dvec3& o, const glm::dvec3& d, double t) const;
  // The fog's extinction at height z (1/m).
  double sigma_at(double z) const;
};

// The fog of `p` at time t (height keys interpolated linearly, constant outside).
FogState fog_at(const FogParams& p, double t);

}  // namespace ambisim
