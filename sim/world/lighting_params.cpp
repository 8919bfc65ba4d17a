#include "sim/world/lighting_params.h"

#include <cstdio>

#include "sim/base/json_reader.h"

namespace ambisim {
namespace {

Rgb read_rgb(ObjectReader& r, const char* key, const Rgb& fallback) {
  // Stored as float: bounded far below FLT_MAX so that radiance stays finite.
  const glm::dvec3 v = r.vec3(key, glm::dvec3(fallback), Range::closed(0.0, 1e6));
  return Rgb(v);
}

bool leap(int y) { return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0; }

int days_in_month(int y, int m) {
  static constexpr int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  return m == 2 && leap(y) ? 29 : kDays[m - 1];
}

// "YYYY-MM-DD", years 1901-2099 (the range of NOAA's stated accuracy).
void read_date(ObjectReader& r, SunPathParams& p) {
  const std::string s = r.string("date");
  int y = 0, m = 0, d = 0;
  char extra = 0;
  if (std::sscanf(s.c_str(), "%4d-%2d-%2d%c", &y, &m, &d, &extra) != 3 || s.size() != 10) {
    r.fail("date", "must be a date \"YYYY-MM-DD\", got \"" + s + "\"");
  }
  if (y < 1901 || y > 2099) r.fail("date", "year must be in 1901..2099, got " + s);
  if (m < 1 || m > 12 || d < 1 || d > days_in_month(y, m)) r.fail("date", "no such day: " + s);
  p.year = y;
  p.month = m;
  p.day = d;
}

// "HH:MM" or "HH:MM:SS", local time, 00:00 to 24:00.
double read_clock(ObjectReader& r, const char* key) {
  const std::string s = r.string(key);
  int h = 0, m = 0, sec = 0;
  char extra = 0;
  const int n = std::sscanf(s.c_str(), "%2d:%2d:%2d%c", &h, &m, &sec, &extra);
  const bool ok = (n == 2 && s.size() == 5) || (n == 3 && s.size() == 8);
  if (!ok || h < 0 || h > 24 || m < 0 || m > 59 || sec < 0 || sec > 59 ||
      (h == 24 && (m > 0 || sec > 0))) {
    r.fail(key, "must be a local time \"HH:MM\" or \"HH:MM:SS\", got \"" + s + "\"");
  }
  return h * 3600.0 + m * 60.0 + sec;
}

SunPathParams parse_sun_path(ObjectReader& r) {
  SunPathParams p;
  const std::string type = r.choice("type", "solar", {"solar", "keyframes"});
  if (type == "solar") {
    p.type = SunPathParams::Type::solar;
    read_date(r, p);
    p.latitude_deg = r.number("latitude_deg", Range::closed(-90.0, 90.0));
    p.longitude_deg = r.number("longitude_deg", p.longitude_deg, Range::closed(-180.0, 180.0));
    p.utc_offset_h = r.number("utc_offset_h", p.utc_offset_h, Range::closed(-14.0, 14.0));
    p.start_s = read_clock(r, "start");
    p.time_scale = r.number("time_scale", p.time_scale, Range::closed(0.0, 1e5));
  } else {
    p.type = SunPathParams::Type::keyframes;
    for (auto& k : r.objects("keys")) {
      SunPathParams::Key key;
      key.time_s = k.number("time_s", Range::closed(0.0, 86400.0 * 366));
      key.elevation_deg = k.number("elevation_deg", Range::closed(-90.0, 90.0));
      key.azimuth_deg = k.number("azimuth_deg", Range::closed(-720.0, 720.0));
      if (!p.keys.empty() && !(key.time_s > p.keys.back().time_s)) {
        k.fail("time_s", "must be greater than the previous key's");
      }
      k.finish();
      p.keys.push_back(key);
    }
    if (p.keys.empty()) r.fail("keys", "needs at least one key");
  }
  r.finish();
  return p;
}

}  // namespace

SunParams parse_sun(ObjectReader& r, SkyParams::Model sky) {
  SunParams s;
  if (sky == SkyParams::Model::preetham) {
    for (const char* key : {"colour", "radiance_ratio", "disc_solid_angle_sr"}) {
      if (r.has(key)) {
        r.fail(key,
               "only the gradient sky's sun takes it (the Preetham sky's atmosphere sets the "
               "sun's colour and irradiance); set /world/sky/model to \"gradient\" or remove it");
      }
    }
  }
  s.enabled = r.boolean("enabled", s.enabled);
  const bool moving = r.has("path");
  if (moving && (r.has("elevation_deg") || r.has("azimuth_deg"))) {
    r.fail("path", "give either a path or a fixed elevation_deg/azimuth_deg, not both");
  }
  s.elevation_deg = r.number("elevation_deg", s.elevation_deg, Range::closed(-90.0, 90.0));
  s.azimuth_deg = r.number("azimuth_deg", s.azimuth_deg, Range::closed(-360.0, 360.0));
  if (auto p = r.optional_object("path")) s.path = parse_sun_path(*p);
  s.colour = read_rgb(r, "colour", s.colour);
  s.radiance_ratio = r.number("radiance_ratio", s.radiance_ratio, Range::closed(0.0, 1e9));
  s.disc_solid_angle_sr =
      r.number("disc_solid_angle_sr", s.disc_solid_angle_sr, {0.0, 0.1, true, false});
  r.finish();
  return s;
}

SkyParams parse_sky(ObjectReader& r) {
  SkyParams s;
  // The uniform test sky is a gradient sky with one colour (it predates the model choice).
  const bool uniform = r.boolean("uniform", false);
  s.model =
      r.choice("model", uniform ? "gradient" : "preetham", {"preetham", "gradient"}) == "gradient"
          ? SkyParams::Model::gradient
          : SkyParams::Model::preetham;
  if (uniform && s.model != SkyParams::Model::gradient) {
    r.fail("uniform", "a uniform sky is a gradient sky: model must be \"gradient\"");
  }
  s.uniform = uniform;
  if (s.model == SkyParams::Model::gradient && r.has("turbidity")) {
    r.fail("turbidity", "only the Preetham sky has a turbidity (model is \"gradient\")");
  }
  if (s.model == SkyParams::Model::preetham) {
    for (const char* key : {"zenith", "horizon", "uniform_radiance"}) {
      if (r.has(key)) {
        r.fail(key, "only the gradient sky takes it (model is \"preetham\")");
      }
    }
  }
  s.turbidity = r.number("turbidity", s.turbidity, Range::closed(2.0, 10.0));
  s.zenith = read_rgb(r, "zenith", s.zenith);
  s.horizon = read_rgb(r, "horizon", s.horizon);
  s.uniform_radiance = read_rgb(r, "uniform_radiance", s.uniform_radiance);
  r.finish();
  return s;
}

CloudParams parse_clouds(ObjectReader& r, std::uint64_t world_seed) {
  CloudParams c;
  c.enabled = r.boolean("enabled", true);
  c.coverage = r.number("coverage", c.coverage, Range::unit());
  c.scale_m = r.number("scale_m", c.scale_m, Range::closed(10.0, 1e5));
  c.softness = r.number("softness", c.softness, Range::closed(0.01, 1.0));
  c.altitude_m = r.number("altitude_m", c.altitude_m, Range::closed(10.0, 2e4));
  c.opacity = r.number("opacity", c.opacity, Range::unit());
  c.wind_mps = r.number("wind_mps", c.wind_mps, Range::closed(0.0, 200.0));
  c.wind_from_deg = r.number("wind_from_deg", c.wind_from_deg, Range::closed(-360.0, 360.0));
  c.seed = r.seed("seed", world_seed);
  r.finish();
  return c;
}

LampParams parse_lamps(ObjectReader& r) {
  LampParams l;
  l.enabled = r.boolean("enabled", true);
  l.spacing_m = r.number("spacing_m", l.spacing_m, Range::closed(2.0, 1e4));
  l.height_m = r.number("height_m", l.height_m, Range::closed(1.0, 100.0));
  l.offset_m = r.number("offset_m", l.offset_m, Range::closed(-1.0, 1e3));
  l.colour = read_rgb(r, "colour", l.colour);
  l.intensity_kcd = r.number("intensity_kcd", l.intensity_kcd, Range::closed(0.0, 1e4));
  l.cone_deg = r.number("cone_deg", l.cone_deg, Range::closed(10.0, 90.0));
  const bool scheduled = r.has("schedule");
  if (scheduled && r.has("on_below_elevation_deg")) {
    r.fail("schedule", "give either a schedule or on_below_elevation_deg, not both");
  }
  l.on_below_elevation_deg =
      r.number("on_below_elevation_deg", l.on_below_elevation_deg, Range::closed(-90.0, 90.0));
  if (scheduled) {
    for (auto& e : r.objects("schedule")) {
      LampParams::Switch s;
      s.time_s = e.number("time_s", Range::closed(0.0, 86400.0 * 366));
      s.on = e.boolean("on", true);
      if (!l.schedule.empty() && !(s.time_s > l.schedule.back().time_s)) {
        e.fail("time_s", "must be greater than the previous switch's");
      }
      e.finish();
      l.schedule.push_back(s);
    }
    if (l.schedule.empty()) r.fail("schedule", "needs at least one switch");
  }
  r.finish();
  return l;
}

FogParams parse_fog(ObjectReader& r) {
  FogParams f;
  f.extinction_per_m = r.number("extinction_per_m", f.extinction_per_m, Range::closed(0.0, 1.0));
  f.colour = read_rgb(r, "colour", f.colour);
  f.sky_distance_m = r.number("sky_distance_m", f.sky_distance_m, Range::non_negative());
  if (auto h = r.optional_object("height")) {
    f.height_enabled = true;
    f.falloff_m = h->number("falloff_m", f.falloff_m, Range::closed(0.1, 1e4));
    if (h->has("keys") && (h->has("density_per_m") || h->has("base_m"))) {
      h->fail("keys", "give either keys or one density_per_m/base_m, not both");
    }
    if (h->has("keys")) {
      for (auto& k : h->objects("keys")) {
        FogParams::HeightKey key;
        key.time_s = k.number("time_s", Range::closed(0.0, 86400.0 * 366));
        key.density_per_m = k.number("density_per_m", Range::closed(0.0, 1.0));
        key.base_m = k.number("base_m", Range::closed(-1e4, 1e5));
        if (!f.height_keys.empty() && !(key.time_s > f.height_keys.back().time_s)) {
          k.fail("time_s", "must be greater than the previous key's");
        }
        k.finish();
        f.height_keys.push_back(key);
      }
      if (f.height_keys.empty()) h->fail("keys", "needs at least one key");
    } else {
      FogParams::HeightKey key;
      key.density_per_m = h->number("density_per_m", Range::closed(0.0, 1.0));
      key.base_m = h->number("base_m", 0.0, Range::closed(-1e4, 1e5));
      f.height_keys.push_back(key);
    }
    h->finish();
  }
  r.finish();
  return f;
}

bool LightingParams::is_static() const {
  const bool fog_fixed = !fog.height_enabled || fog.height_keys.size() <= 1;
  const bool lamps_fixed =
      !lamps.enabled || (lamps.schedule.empty() && sun.path.type == SunPathParams::Type::fixed) ||
      (!lamps.schedule.empty() && lamps.schedule.size() == 1 && lamps.schedule[0].time_s == 0.0);
  return sun.path.type == SunPathParams::Type::fixed && !clouds.enabled && lamps_fixed && fog_fixed;
}

bool LightingParams::is_legacy() const {
  return sky.model == SkyParams::Model::gradient && sun.path.type == SunPathParams::Type::fixed &&
         !clouds.enabled && !lamps.enabled && !fog.height_enabled;
}

}  // namespace ambisim
