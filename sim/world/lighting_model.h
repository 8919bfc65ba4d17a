#pragma once
// The world's lighting as a function of simulated time (SPEC 1b). A LightingModel is built per
// run from the world's parameters; state_at(t) gives the LightingState at t, and
// illumination_at(t) what the renderer asks of it (illumination.h). Nothing here depends on a
// planner: captures, the reference and the views all see the world as lit at their time.
//
// The pieces: the sun (fixed, NOAA's solar position for a date and place, or keyframes) and its
// irradiance (legacy constant with the gradient sky; through the atmosphere with the Preetham
// sky), the sky (gradient or Preetham with twilight below the horizon), drifting clouds
// (cloud_layer.h), street lamps (street_lamps.h), height fog (height_fog.h), and terrain
// shadows (the world's map for a fixed sun; sun_shadows.h for a moving one).
#include <memory>
#include <optional>

#include <glm/vec3.hpp>

#include "sim/colour/rgb.h"
#include "sim/planner.h"
#include "sim/sh/sh9.h"
#include "sim/world/cloud_layer.h"
#include "sim/world/height_fog.h"
#include "sim/world/lighting_params.h"
#include "sim/world/sky_model.h"
#include "sim/world/street_lamps.h"
#include "sim/world/sun_shadows.h"

namespace ambisim {

class World;

// The lighting at one moment.
struct LightingState {
  double time = 0.0;
  bool legacy = false;  // the first model: render with the world's precomputed radiance
  // Sun (toward it), whether it shines, its apparent elevation, and its irradiance on a plane
  // facing it (klx with the Preetham sky; legacy units with the gradient).
  glm::dvec3 sun_dir{0.0, 0.0, 1.0};
  bool sun_on = false;
  double sun_elevation_deg = 0.0;
  Rgb e_sun{0.0f};
  // Sky: the gradient (legacy units) or Preetham scaled by the twilight factor.
  SkyParams::Model sky_model = SkyParams::Model::gradient;
  SkyParams gradient;
  std::optional<PreethamSky> preetham;
  double sky_scale = 1.0;  // twilight factor times the unit conversion
  Rgb night_floor{0.0f};   // added below the horizon (airglow, starlight)
  // The sky's radiance in SH9 (clouds blended in at their mean cover), zero below the horizon:
  // what surfaces are lit by (their sky irradiance, one bounce, no terrain occlusion).
  Sh9Rgb sky_sh;
  Rgb sky_irradiance_up{0.0f};  // on an upward surface
  // Clouds, lamps, fog.
  const CloudLayer* clouds = nullptr;
  Rgb cloud_radiance{0.0f};
  const StreetLamps* lamps = nullptr;
  double lamp_level = 0.0;
  FogState fog;
  Rgb fog_inscatter{0.0f};
  double fog_sky_distance_m = 2000.0;
  // Shadows of a moving sun, set to this time (null: the world's own map).
  const SunShadows* shadows = nullptr;

  // The clear (cloudless) sky toward unit d.
  Rgb clear_sky(const glm::dvec3& d) const;
  // The sky seen from o toward unit d (clouds included, no fog).
  Rgb sky(const glm::dvec3& o, const glm::dvec3& d) const;
  // Sky irradiance on a surface of unit normal n (from sky_sh, >= 0).
  Rgb sky_irradiance(const glm::dvec3& n) const;
};

class LightingModel {
 public:
  LightingModel(const World& world);
  LightingModel(const LightingModel&) = delete;
  LightingModel& operator=(const LightingModel&) = delete;

  bool is_static() const { return static_; }
  bool is_legacy() const { return legacy_; }
  // The state at t. With a moving sun the shadows are set to t: a state is valid until the next
  // call of state_at (the renderer works one time at a time).
  const LightingState& state_at(double t);
  // The sun at t (direction, on, apparent elevation), cheap.
  SunShadows::Sun sun_at(double t, double* apparent_elevation_deg = nullptr) const;
  // What a planner may know at t (planner.h). Does not move the state's shadows.
  LightingInfo info_at(double t);
  // How fast the light changes at a ground point p at time t (1/s), lamps aside: the sun's, the
  // sky's and the fog's rate, or the cloud shadows' drift there if faster.
  double local_change_rate(const glm::dvec3& p, double t);

  const CloudLayer* clouds() const { return clouds_.get(); }
  const StreetLamps* lamps() const { return lamps_.get(); }

 private:
  LightingState compute(double t, bool set_shadows = true);
  // The scalars the change rate is taken from (no sky projection: cheap).
  struct Scalars {
    glm::dvec3 sun_dir{0.0, 0.0, 1.0};
    double sun_elevation_deg = 0.0;
    double sun = 0.0;         // sun luminance (irradiance facing it)
    double sky_zenith = 0.0;  // zenith luminance
    double fog_density = 0.0;
    double lamp_level = 0.0;
  };
  Scalars scalars_at(double t) const;

  LightingParams p_;
  bool static_ = true, legacy_ = false;
  std::unique_ptr<CloudLayer> clouds_;
  std::unique_ptr<StreetLamps> lamps_;
  std::unique_ptr<SunShadows> shadows_;
  LightingState state_;
  bool have_state_ = false;
  LightingInfo info_;
  double info_time_ = 0.0;
  bool have_info_ = false;
};

}  // namespace ambisim
