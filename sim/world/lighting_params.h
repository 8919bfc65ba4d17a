#pragma once
// The validated description of the world's lighting over time (SPEC sections 1 and 1b): the sun
// (fixed, or moving along the solar path of a date and place, or along keyframes), the sky
// (the legacy gradient, or the Preetham 1999 clear-sky model tied to the sun), drifting clouds,
// street lamps along the road, and fog (homogeneous and exponential height fog whose density
// and base can change over time). Parsed from the world section (world_params.h); every key is
// documented in scenarios/README.md.
#include <cstdint>
#include <string>
#include <vector>

#include "sim/colour/rgb.h"

namespace ambisim {

class ObjectReader;

// The sun's direction over time.
struct SunPathParams {
  enum class Type { fixed, solar, keyframes };
  Type type = Type::fixed;
  // solar: the NOAA solar-position algorithm at this place and date, starting at local time
  // start_s (seconds after local midnight) and running time_scale simulated-day seconds per
  // second of the run.
  int year = 2026, month = 6, day = 21;
  double latitude_deg = 57.7;   // north positive
  double longitude_deg = 12.0;  // east positive
  double utc_offset_h = 2.0;    // local time = UTC + offset
  double start_s = 12.0 * 3600.0;
  double time_scale = 1.0;
  // keyframes: elevation and azimuth linear in time between keys, constant outside.
  struct Key {
    double time_s = 0.0;
    double elevation_deg = 0.0;
    double azimuth_deg = 0.0;
  };
  std::vector<Key> keys;
};

struct SunParams {
  bool enabled = true;
  double elevation_deg = 40.0;  // fixed sun: above the horizon, -90..90 (<= 0: no direct light)
  double azimuth_deg = 200.0;   // compass: 0 = north (+y), 90 = east (+x)
  SunPathParams path;           // fixed unless a path is given
  // Gradient sky only (legacy units): the sun's tint and its radiance relative to the sky's
  // zenith; with the Preetham sky the atmosphere gives colour and irradiance instead.
  Rgb colour{1.0f, 0.95f, 0.85f};
  double radiance_ratio = 1.0e5;  // sun radiance / sky zenith radiance (thesis 10.2.3)
  double disc_solid_angle_sr = 6.8e-5;
};

struct SkyParams {
  enum class Model { preetham, gradient };
  Model model = Model::preetham;
  double turbidity = 3.0;  // Preetham: 2 (very clear) .. 10 (hazy)
  // gradient (the first model, O(1) radiance units):
  bool uniform = false;             // true: radiance `uniform_radiance` in every direction
  Rgb zenith{0.25f, 0.45f, 1.0f};   // radiance straight up
  Rgb horizon{0.75f, 0.85f, 1.0f};  // radiance at and below the horizon
  Rgb uniform_radiance{1.0f, 1.0f, 1.0f};
};

// A seeded procedural cloud layer drifting with the wind.
struct CloudParams {
  bool enabled = false;
  double coverage = 0.4;       // share of the sky covered, 0..1
  double scale_m = 700.0;      // size of the larger cloud features
  double softness = 0.15;      // edge width, as a share of the coverage field's range
  double altitude_m = 1500.0;  // above the world's lowest surface
  double opacity = 0.85;       // share of the sun a cloud stops
  double wind_mps = 10.0;
  double wind_from_deg = 270.0;  // compass direction the wind comes from
  std::uint64_t seed = 1;
};

// Street lamps along both sides of the road.
struct LampParams {
  bool enabled = false;
  double spacing_m = 40.0;  // along the road, each side
  double height_m = 10.0;   // above the road surface
  double offset_m = -1.0;   // from the centre line; < 0: the road's edge plus 1 m
  Rgb colour{1.0f, 0.78f, 0.5f};
  double intensity_kcd = 3.0;  // luminous intensity straight down (kcd; irradiance in klx)
  double cone_deg = 70.0;      // half angle of the light cone, softened over its last 10 deg
  // On while the sun is below this elevation (the usual photocell switch), unless a schedule
  // of switching times is given.
  double on_below_elevation_deg = 2.0;
  struct Switch {
    double time_s = 0.0;
    bool on = true;
  };
  std::vector<Switch> schedule;
};

struct FogParams {
  // Homogeneous fog (the first model): L T + L_fog (1 - T), T = exp(-sigma t).
  double extinction_per_m = 0.0;   // sigma; 0 = no fog
  Rgb colour{0.7f, 0.75f, 0.8f};   // in-scattered radiance L_fog (legacy) or fog albedo
  double sky_distance_m = 2000.0;  // rays that escape to the sky are fogged over this length
  // Exponential height fog (the games' standard): sigma(z) = density exp(-(z - base) / falloff),
  // with density and base linear in time between keys.
  struct HeightKey {
    double time_s = 0.0;
    double density_per_m = 0.0;
    double base_m = 0.0;
  };
  bool height_enabled = false;
  double falloff_m = 15.0;
  std::vector<HeightKey> height_keys;  // sorted by time, at least one
};

struct LightingParams {
  SunParams sun;
  SkyParams sky;
  CloudParams clouds;
  LampParams lamps;
  FogParams fog;
  // True when nothing changes over time: a fixed sun, no clouds, no lamp that switches, no
  // changing fog.
  bool is_static() const;
  // True for exactly the first model (gradient sky, fixed sun, homogeneous fog only), whose
  // rendering stays bit-for-bit what it was.
  bool is_legacy() const;
};

// Readers of the world's "sun", "sky", "clouds", "lamps" and "fog" objects (keys in
// scenarios/README.md); each calls r.finish(). A key that only the other sky model uses is an
// error, not silently ignored: the sun's colour, radiance_ratio and disc_solid_angle_sr and the
// sky's zenith, horizon and uniform_radiance are the gradient sky's, turbidity is Preetham's.
SunParams parse_sun(ObjectReader& r, SkyParams::Model sky);
SkyParams parse_sky(ObjectReader& r);
CloudParams parse_clouds(ObjectReader& r, std::uint64_t world_seed);
LampParams parse_lamps(ObjectReader& r);
FogParams parse_fog(ObjectReader& r);

}  // namespace ambisim
