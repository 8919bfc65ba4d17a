#pragma once
// A seeded procedural cloud layer drifting with the wind (the animated noise textures of seed
// 004, section 2.3.2): a tileable fractal value-noise field on a horizontal plane at the layer's
// altitude, thresholded at the quantile that gives the requested coverage and softened over
// `softness` of the field's range. The field moves with the wind: cover(x, y, t) =
// field(x - w_x t, y - w_y t). Clouds shadow the sun on the ground (the layer point along the
// sun direction) and are seen in the sky (the layer point along the view direction).
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "sim/world/lighting_params.h"

namespace ambisim {

class CloudLayer {
 public:
  // layer_z: the layer's absolute height.
  CloudLayer(const CloudParams& p, double layer_z);

  // Cover in [0, 1] at layer position (x, y) at time t (bilinear in the texture).
  double cover(double x, double y, double t) const;
  // Share of the sun reaching p through the layer along the unit sun direction s (1 when the
  // sun is below the layer's plane or p above it).
  double sun_transmittance(const glm::dvec3& p, const glm::dvec3& s, double t) const;
  // Cover seen from o along unit d (0 for rays below the horizontal or above the layer).
  double cover_along(const glm::dvec3& o, const glm::dvec3& d, double t) const;
  // How fast the cover changes at a ground point where the sun comes from s: |grad c . w|
  // (1/s), for planners' refresh decisions (what a weather system knows).
  double change_rate(const glm::dvec3& p, const glm::dvec3& s, double t) const;

  double mean_cover() const { return mean_; }
  double opacity() const { return p_.opacity; }
  double layer_z() const { return z_; }
  glm::dvec2 wind() const { return wind_; }

  static constexpr int kTexels = 256;  // per side of the tile

 private:
  double sample(double u, double v) const;  // texel units, periodic

  CloudParams p_;
  double z_;
  glm::dvec2 wind_{0.0};
  double texel_m_ = 1.0;  // tile = kTexels texels = 8 x scale_m
  std::vector<float> c_;  // cover per texel (after threshold and softening)
  double mean_ = 0.0;
};

}  // namespace ambisim
