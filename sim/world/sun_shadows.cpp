#include "sim/world/sun_shadows.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "sim/world/shadow_heights.h"
#include "sim/world/world.h"

namespace ambisim {
namespace {

constexpr std::size_t kMapsKept = 4;
// The search step for the next key: fine enough that the sun never travels more than the key
// step between probes at any realistic rate (it is refined by bisection).
constexpr double kProbeS = 0.25;

double angle(const SunShadows::Sun& a, const SunShadows::Sun& b) {
  return std::acos(std::clamp(glm::dot(a.dir, b.dir), -1.0, 1.0));
}

}  // namespace

SunShadows::SunShadows(const World& world, SunAt sun_at, double max_step_deg)
    : world_(world),
      sun_at_(std::move(sun_at)),
      max_step_rad_(max_step_deg * 3.14159265358979323846 / 180.0) {}

std::vector<float> SunShadows::exact_map(double t) const {
  const Sun s = sun_at_(t);
  return shadow_heights(world_.surface_columns(), world_.nx(), world_.ny(), world_.cell_m(), s.dir,
                        s.on);
}

std::size_t SunShadows::key_containing(double t) {
  while (keys_.back() <= t) {
    // The next key: the first time the sun has moved max_step from the last key (or switched
    // on or off), found by stepping and bisecting.
    const double k0 = keys_.back();
    const Sun s0 = sun_at_(k0);
    double lo = k0, hi = k0 + kProbeS;
    while (angle(s0, sun_at_(hi)) < max_step_rad_ && sun_at_(hi).on == s0.on) {
      lo = hi;
      hi += kProbeS;
      if (hi - k0 > 86400.0) break;  // a sun that never moves enough: one key a day
    }
    for (int i = 0; i < 30; ++i) {
      const double mid = 0.5 * (lo + hi);
      const Sun sm = sun_at_(mid);
      if (angle(s0, sm) < max_step_rad_ && sm.on == s0.on) {
        lo = mid;
      } else {
        hi = mid;
      }
    }
    keys_.push_back(std::max(hi, k0 + 1e-6));
  }
  const auto it = std::upper_bound(keys_.begin(), keys_.end(), t);
  return static_cast<std::size_t>(it - keys_.begin()) - 1;
}

const SunShadows::Map& SunShadows::map_for(std::size_t key) {
  for (auto it = maps_.begin(); it != maps_.end(); ++it) {
    if (it->key == key) {
      maps_.splice(maps_.begin(), maps_, it);
      return maps_.front();
    }
  }
  maps_.push_front({key, exact_map(keys_[key])});
  ++maps_computed_;
  if (maps_.size() > kMapsKept) maps_.pop_back();
  return maps_.front();
}

void SunShadows::set_time(double t) {
  t_ = t;
  const std::size_t k = key_containing(std::max(t, 0.0));
  // std::list keeps its elements in place when they move to the front: both pointers stay valid
  // while at most kMapsKept - 2 other maps are added.
  lo_ = &map_for(k);
  hi_ = &map_for(k + 1);
  const double span = keys_[k + 1] - keys_[k];
  f_ = span > 0.0 ? static_cast<float>(std::clamp((t - keys_[k]) / span, 0.0, 1.0)) : 0.0f;
}

float SunShadows::height(std::size_t cell) const {
  const float a = lo_->height[cell], b = hi_->height[cell];
  // Where either key has no sun (+inf) or nothing shadowing, do not blend across the change.
  if (!std::isfinite(a) || !std::isfinite(b)) return f_ < 0.5f ? a : b;
  if (a <= kNoShadow || b <= kNoShadow) return f_ < 0.5f ? a : b;
  return a + (b - a) * f_;
}

}  // namespace ambisim
