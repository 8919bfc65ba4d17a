#pragma once
// What the renderer asks about the light at one moment: the radiance leaving what a ray hit
// (a column's top or wall, the far ground) toward the ray's origin, the sky along an escaping
// ray, and the fog between. Two implementations behind one type: the world's own unchanging
// lighting (the first model: the radiance precomputed per cell, bit for bit as before), and a
// LightingState (everything evaluated at the hit: sun with its shadows and clouds, sky
// irradiance, street lamps, height fog).
//
// Layers (for planners that store the lamps apart, thesis 7.5.3): `base` renders everything but
// the lamps, `lamps` only the lamps' light at full power (no sky, no fog in-scatter, only the
// fog's attenuation), `all` both at the lamps' current level; all = base + level * lamps.
#include <glm/vec3.hpp>

#include "sim/colour/rgb.h"
#include "sim/world/lighting_model.h"
#include "sim/world/world.h"

namespace ambisim {

enum class LightLayer { all, base, lamps };

class Illumination {
 public:
  // The world's lighting at time 0 (the first model's precomputed radiance, or
  // World::start_lighting()).
  explicit Illumination(const World& w);
  Illumination(const World& w, const LightingState& state, LightLayer layer = LightLayer::all);

  Rgb sky(const glm::dvec3& o, const glm::dvec3& d) const;
  Rgb far_ground(const glm::dvec3& o, const glm::dvec3& d, double t) const;
  // A column face hit at distance t along unit d from o (z of the hit = o.z + d.z t).
  Rgb column(int ix, int iy, ColumnFace face, const glm::dvec3& o, const glm::dvec3& d,
             double t) const;

  const World& world() const { return w_; }
  const LightingState* state() const { return s_; }
  LightLayer layer() const { return layer_; }

 private:
  Rgb fogged(const Rgb& l, const glm::dvec3& o, const glm::dvec3& d, double t) const;
  Rgb lit_surface(const Rgb& albedo, const glm::dvec3& p, const glm::dvec3& n, bool sunlit) const;
  float shadow_height(int ix, int iy) const;

  const World& w_;
  const LightingState* s_ = nullptr;  // null: the world's precomputed lighting
  LightLayer layer_ = LightLayer::all;
};

}  // namespace ambisim
