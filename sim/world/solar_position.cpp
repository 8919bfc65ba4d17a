#include "sim/world/solar_position.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace ambisim {
namespace {

double rad(double d) { return d * std::numbers::pi / 180.0; }
double deg(double r) { return r * 180.0 / std::numbers::pi; }
// Excel's MOD: the result takes the divisor's sign (never negative here).
double excel_mod(double a, double n) { return a - n * std::floor(a / n); }

// Meeus, "Astronomical Algorithms", ch. 7: the Julian Day at 0h UT of a Gregorian date.
double julian_day_0h(int y, int m, int d) {
  if (m <= 2) {
    y -= 1;
    m += 12;
  }
  const double a = std::floor(y / 100.0);
  const double b = 2.0 - a + std::floor(a / 4.0);
  return std::floor(365.25 * (y + 4716)) + std::floor(30.6001 * (m + 1)) + d + b - 1524.5;
}

}  // namespace

double noaa_refraction_deg(double h) {
  // The spreadsheet's column AF: arc seconds, / 3600. (Its h < -0.575 constant is -20.772; the
  // web calculator's -20.774 differs by at most 2e-6 deg.)
  const double t = std::tan(rad(h));
  double arcsec;
  if (h > 85.0) {
    arcsec = 0.0;
  } else if (h > 5.0) {
    arcsec = 58.1 / t - 0.07 / (t * t * t) + 0.000086 / (t * t * t * t * t);
  } else if (h > -0.575) {
    arcsec = 1735.0 + h * (-518.2 + h * (103.4 + h * (-12.79 + h * 0.711)));
  } else {
    arcsec = -20.772 / t;
  }
  return arcsec / 3600.0;
}

SolarPosition noaa_solar_position(int year, int month, int day, double local_minutes,
                                  double latitude_deg, double longitude_deg, double utc_offset_h) {
  SolarPosition s;
  const double phi = latitude_deg, lon = longitude_deg, tz = utc_offset_h;
  const double day_fraction = local_minutes / 1440.0;
  s.julian_day = julian_day_0h(year, month, day) + day_fraction - tz / 24.0;
  const double T = (s.julian_day - 2451545.0) / 36525.0;
  s.julian_century = T;
  s.geom_mean_long_deg = excel_mod(280.46646 + T * (36000.76983 + T * 0.0003032), 360.0);
  s.geom_mean_anom_deg = 357.52911 + T * (35999.05029 - 0.0001537 * T);
  s.eccentricity = 0.016708634 - T * (0.000042037 + 1.267e-7 * T);
  const double M = s.geom_mean_anom_deg, e = s.eccentricity, L0 = s.geom_mean_long_deg;
  s.eq_of_centre_deg = std::sin(rad(M)) * (1.914602 - T * (0.004817 + 0.000014 * T)) +
                       std::sin(rad(2 * M)) * (0.019993 - 0.000101 * T) +
                       std::sin(rad(3 * M)) * 0.000289;
  s.true_long_deg = L0 + s.eq_of_centre_deg;
  s.true_anom_deg = M + s.eq_of_centre_deg;
  s.radius_au = (1.000001018 * (1 - e * e)) / (1 + e * std::cos(rad(s.true_anom_deg)));
  s.apparent_long_deg = s.true_long_deg - 0.00569 - 0.00478 * std::sin(rad(125.04 - 1934.136 * T));
  s.mean_obliquity_deg =
      23 + (26 + ((21.448 - T * (46.815 + T * (0.00059 - T * 0.001813)))) / 60) / 60;
  s.obliquity_deg = s.mean_obliquity_deg + 0.00256 * std::cos(rad(125.04 - 1934.136 * T));
  const double lam = s.apparent_long_deg, eps = s.obliquity_deg;
  // Excel ATAN2(x, y) is C's atan2(y, x).
  s.right_ascension_deg =
      deg(std::atan2(std::cos(rad(eps)) * std::sin(rad(lam)), std::cos(rad(lam))));
  s.declination_deg = deg(std::asin(std::sin(rad(eps)) * std::sin(rad(lam))));
  const double delta = s.declination_deg;
  s.var_y = std::tan(rad(eps / 2)) * std::tan(rad(eps / 2));
  const double y = s.var_y;
  s.equation_of_time_min =
      4 * deg(y * std::sin(2 * rad(L0)) - 2 * e * std::sin(rad(M)) +
              4 * e * y * std::sin(rad(M)) * std::cos(2 * rad(L0)) -
              0.5 * y * y * std::sin(4 * rad(L0)) - 1.25 * e * e * std::sin(2 * rad(M)));
  const double eot = s.equation_of_time_min;
  const double cos_ha = std::cos(rad(90.833)) / (std::cos(rad(phi)) * std::cos(rad(delta))) -
                        std::tan(rad(phi)) * std::tan(rad(delta));
  s.hour_angle_sunrise_deg =
      std::abs(cos_ha) <= 1.0 ? deg(std::acos(cos_ha)) : std::numeric_limits<double>::quiet_NaN();
  s.solar_noon_day = (720 - 4 * lon - eot + tz * 60) / 1440;
  s.sunrise_day = s.solar_noon_day - s.hour_angle_sunrise_deg * 4 / 1440;
  s.sunset_day = s.solar_noon_day + s.hour_angle_sunrise_deg * 4 / 1440;
  s.true_solar_time_min = excel_mod(day_fraction * 1440 + eot + 4 * lon - 60 * tz, 1440.0);
  const double tst = s.true_solar_time_min;
  s.hour_angle_deg = tst / 4 < 0 ? tst / 4 + 180 : tst / 4 - 180;
  const double H = s.hour_angle_deg;
  const double cos_z = std::sin(rad(phi)) * std::sin(rad(delta)) +
                       std::cos(rad(phi)) * std::cos(rad(delta)) * std::cos(rad(H));
  s.zenith_deg = deg(std::acos(std::clamp(cos_z, -1.0, 1.0)));
  s.elevation_deg = 90 - s.zenith_deg;
  s.refraction_deg = noaa_refraction_deg(s.elevation_deg);
  s.apparent_elevation_deg = s.elevation_deg + s.refraction_deg;
  // Azimuth: the spreadsheet's formula, with the web calculator's guards (a clamped acos; due
  // south or north where the zenith or pole makes it undefined).
  const double denom = std::cos(rad(phi)) * std::sin(rad(s.zenith_deg));
  if (std::abs(denom) <= 0.001) {
    s.azimuth_deg = phi > 0 ? 180.0 : 0.0;
  } else {
    const double a = deg(std::acos(std::clamp(
        ((std::sin(rad(phi)) * std::cos(rad(s.zenith_deg))) - std::sin(rad(delta))) / denom, -1.0,
        1.0)));
    s.azimuth_deg = H > 0 ? excel_mod(a + 180, 360) : excel_mod(540 - a, 360);
  }
  return s;
}

double kasten_young_air_mass(double z) {
  if (!(z <= 90.0)) return std::numeric_limits<double>::quiet_NaN();
  return 1.0 / (std::cos(rad(z)) + 0.50572 * std::pow(96.07995 - z, -1.6364));
}

}  // namespace ambisim
