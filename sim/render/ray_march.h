#pragma once
// Rays through the column world (sim/world/world.h): an accelerated marcher over the maximum mip
// pyramid and a naive fixed-step marcher kept as the reference. Both report the same "hit
// surface" identity (cell, face) and the exact entry distance into that column, computed by
// one shared slab test, so their radiance agrees wherever they hit the same surface.
#include <cstdint>

#include <glm/vec3.hpp>

#include "sim/colour/rgb.h"
#include "sim/world/illumination.h"
#include "sim/world/world.h"

namespace ambisim {

enum class Marcher { accelerated, naive };

enum class HitKind : std::uint8_t { Sky, FarGround, Column };

struct RayHit {
  HitKind kind = HitKind::Sky;
  int ix = -1, iy = -1;  // column (HitKind::Column only)
  ColumnFace face = ColumnFace::Top;
  double t = 0.0;  // distance along the unit direction (Sky: infinity)

  bool same_surface(const RayHit& o) const {
    return kind == o.kind &&
           (kind != HitKind::Column || (ix == o.ix && iy == o.iy && face == o.face));
  }
};

// Naive step as a fraction of the cell size. The naive marcher samples the ray every step
// and tests each cell the last step crossed (no skipping, no hierarchy): the brute-force
// reference for the pyramid traversal.
inline constexpr double kNaiveStepCells = 0.25;

// `d` must be unit length. Rays start at `o` (t = 0).
RayHit march_accelerated(const World& w, const glm::dvec3& o, const glm::dvec3& d);
RayHit march_naive(const World& w, const glm::dvec3& o, const glm::dvec3& d);
RayHit march(const World& w, const glm::dvec3& o, const glm::dvec3& d, Marcher m);

// Outgoing radiance toward the ray origin from what the ray hit, fogged over t, in the light
// of `il` (the world's own static lighting when given the world).
Rgb hit_radiance(const Illumination& il, const glm::dvec3& o, const glm::dvec3& d, const RayHit& h);
Rgb hit_radiance(const World& w, const glm::dvec3& o, const glm::dvec3& d, const RayHit& h);

inline Rgb trace_radiance(const Illumination& il, const glm::dvec3& o, const glm::dvec3& d,
                          Marcher m) {
  return hit_radiance(il, o, d, march(il.world(), o, d, m));
}
inline Rgb trace_radiance(const World& w, const glm::dvec3& o, const glm::dvec3& d, Marcher m) {
  return trace_radiance(Illumination(w), o, d, m);
}

}  // namespace ambisim
