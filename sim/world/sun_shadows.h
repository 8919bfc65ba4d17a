#pragma once
// Terrain shadows of a moving sun. Recomputing the shadow-height map of a 4 km world every frame
// is too slow (about 40 ms per map), so maps are computed at key times no more than
// max_step_deg of sun travel apart and the shadow height is interpolated linearly in time
// between the two maps that bracket the frame. The error of that shortcut against the exact map
// at the frame's own sun direction is measured in tests/sim/world/test_sun_shadows.cpp.
// Maps are computed on first use and the last few kept, so access in time order (the frame
// loop; the reference works in time order) computes each key once.
#include <cstddef>
#include <functional>
#include <list>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

namespace ambisim {

class World;

class SunShadows {
 public:
  // The sun's unit direction at time t and whether it shines (above the horizon).
  struct Sun {
    glm::dvec3 dir{0.0, 0.0, 1.0};
    bool on = false;
  };
  using SunAt = std::function<Sun(double t)>;

  SunShadows(const World& world, SunAt sun_at, double max_step_deg = 1.0);

  // Brackets t by key maps (computing them when needed); height() then answers for t.
  void set_time(double t);
  double time() const { return t_; }
  // The interpolated shadow height of cell (ix, iy) at the set time (+inf: no sun at all).
  float height(std::size_t cell) const;
  // Key times found so far and maps computed (for tests and measurements).
  const std::vector<double>& keys() const { return keys_; }
  std::size_t maps_computed() const { return maps_computed_; }
  // The exact map for the sun at time t (the reference the interpolation is tested against).
  std::vector<float> exact_map(double t) const;

 private:
  struct Map {
    std::size_t key;
    std::vector<float> height;
  };
  std::size_t key_containing(double t);  // index k with keys_[k] <= t < keys_[k + 1]
  const Map& map_for(std::size_t key);

  const World& world_;
  SunAt sun_at_;
  double max_step_rad_;
  std::vector<double> keys_{0.0};
  std::list<Map> maps_;  // most recently used first
  std::size_t maps_computed_ = 0;
  double t_ = 0.0;
  const Map* lo_ = nullptr;
  const Map* hi_ = nullptr;
  float f_ = 0.0f;  // weight of hi_
};

}  // namespace ambisim
