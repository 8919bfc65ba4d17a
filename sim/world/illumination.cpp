#include "sim/world/illumination.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <glm/geometric.hpp>

namespace ambisim {

Illumination::Illumination(const World& w)
    : w_(w), s_(w.params().lighting().is_legacy() ? nullptr : &w.start_lighting()) {}

Illumination::Illumination(const World& w, const LightingState& state, LightLayer layer)
    : w_(w), s_(state.legacy && layer == LightLayer::all ? nullptr : &state), layer_(layer) {}

float Illumination::shadow_height(int ix, int iy) const {
  if (s_ != nullptr && s_->shadows != nullptr) return s_->shadows->height(w_.cell_index(ix, iy));
  return w_.shadow_height(ix, iy);
}

Rgb Illumination::fogged(const Rgb& l, const glm::dvec3& o, const glm::dvec3& d, double t) const {
  const double tau = s_->fog.optical_depth(o, d, t);
  if (!(tau > 0.0)) return l;
  const float tr = static_cast<float>(std::exp(-tau));
  if (layer_ == LightLayer::lamps) return l * tr;  // lamps light surfaces, not the fog
  return l * tr + s_->fog_inscatter * (1.0f - tr);
}

Rgb Illumination::lit_surface(const Rgb& albedo, const glm::dvec3& p, const glm::dvec3& n,
                              bool sunlit) const {
  const LightingState& s = *s_;
  Rgb e(0.0f);
  if (layer_ != LightLayer::lamps) {
    e = s.sky_irradiance(n);
    if (sunlit && s.sun_on) {
      const double c = glm::dot(n, s.sun_dir);
      if (c > 0.0) {
        double tr = 1.0;
        if (s.clouds != nullptr) tr = s.clouds->sun_transmittance(p, s.sun_dir, s.time);
        e += s.e_sun * static_cast<float>(c * tr);
      }
    }
  }
  if (s.lamps != nullptr && layer_ != LightLayer::base) {
    const double level = layer_ == LightLayer::lamps ? 1.0 : s.lamp_level;
    if (level > 0.0) e += s.lamps->irradiance(p, n) * static_cast<float>(level);
  }
  return albedo * e * static_cast<float>(1.0 / std::numbers::pi);
}

Rgb Illumination::sky(const glm::dvec3& o, const glm::dvec3& d) const {
  if (s_ == nullptr) return w_.lighting().sky_ray(d);
  if (layer_ == LightLayer::lamps) return Rgb(0.0f);
  const Rgb l = s_->sky(o, d);
  // An escaping ray: the homogeneous fog over the sky distance (the first model's rule), the
  // height fog over the whole way up.
  double tau = s_->fog.homogeneous_per_m * s_->fog_sky_distance_m;
  FogState height_only = s_->fog;
  height_only.homogeneous_per_m = 0.0;
  tau += height_only.optical_depth(o, d, std::numeric_limits<double>::infinity());
  if (!(tau > 0.0)) return l;
  const float tr = static_cast<float>(std::exp(-tau));
  return l * tr + s_->fog_inscatter * (1.0f - tr);
}

Rgb Illumination::far_ground(const glm::dvec3& o, const glm::dvec3& d, double t) const {
  if (s_ == nullptr) return w_.lighting().apply_fog(w_.far_ground_radiance(), t);
  if (layer_ == LightLayer::lamps) return Rgb(0.0f);
  const glm::dvec3 p = o + d * t;
  return fogged(lit_surface(Rgb(w_.far_ground_albedo()), p, {0.0, 0.0, 1.0}, true), o, d, t);
}

Rgb Illumination::column(int ix, int iy, ColumnFace face, const glm::dvec3& o, const glm::dvec3& d,
                         double t) const {
  if (s_ == nullptr) {
    const Rgb l = (face == ColumnFace::Top || face == ColumnFace::Inside)
                      ? w_.top_radiance(ix, iy)
                      : w_.wall_radiance(ix, iy, face, o.z + d.z * t);
    return w_.lighting().apply_fog(l, t);
  }
  const glm::dvec3 p = o + d * t;
  const glm::dvec3 n = w_.face_normal(ix, iy, face);
  const bool sunlit = p.z >= shadow_height(ix, iy);
  return fogged(lit_surface(w_.cell_albedo(ix, iy), p, n, sunlit), o, d, t);
}

}  // namespace ambisim
