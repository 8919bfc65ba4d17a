#pragma once
// The sun's position from the date, the time and the place: NOAA's solar-position algorithm,
// exactly as in NOAA_Solar_Calculations_day.xls (NOAA/ESRL/GMD Solar Calculator, after Meeus,
// "Astronomical Algorithms"), including its refraction correction. Valid 1901-2099 (the
// spreadsheet's range). Its angles agree with NREL's SPA to about 0.005 deg in elevation and
// azimuth (tests/sim/world/test_solar_position.cpp checks the spreadsheet's own values to 1e-9
// and SPA's example to 0.01 deg). Angles in degrees; latitude + north, longitude + east,
// utc_offset + east of UTC (hours, standard time); azimuth clockwise from north.
namespace ambisim {

struct SolarPosition {
  // Every intermediate of the spreadsheet, in its order (units as the spreadsheet's).
  double julian_day = 0.0;
  double julian_century = 0.0;
  double geom_mean_long_deg = 0.0;
  double geom_mean_anom_deg = 0.0;
  double eccentricity = 0.0;
  double eq_of_centre_deg = 0.0;
  double true_long_deg = 0.0;
  double true_anom_deg = 0.0;
  double radius_au = 0.0;
  double apparent_long_deg = 0.0;
  double mean_obliquity_deg = 0.0;
  double obliquity_deg = 0.0;
  double right_ascension_deg = 0.0;
  double declination_deg = 0.0;
  double var_y = 0.0;
  double equation_of_time_min = 0.0;
  double hour_angle_sunrise_deg = 0.0;  // NaN in polar day or night
  double solar_noon_day = 0.0;          // local standard time, fraction of a day
  double sunrise_day = 0.0;
  double sunset_day = 0.0;
  double true_solar_time_min = 0.0;
  double hour_angle_deg = 0.0;
  double zenith_deg = 0.0;     // geometric
  double elevation_deg = 0.0;  // geometric
  double refraction_deg = 0.0;
  double apparent_elevation_deg = 0.0;  // corrected for refraction
  double azimuth_deg = 0.0;
};

// year, month (1-12), day (1-31); local_minutes after local midnight (standard time).
SolarPosition noaa_solar_position(int year, int month, int day, double local_minutes,
                                  double latitude_deg, double longitude_deg, double utc_offset_h);

// NOAA's refraction correction (deg) for a geometric elevation h (deg).
double noaa_refraction_deg(double h);

// Relative optical air mass, Kasten & Young 1989, for the apparent (refraction-corrected)
// zenith angle z in degrees: 1 / (cos z + 0.50572 (96.07995 - z)^-1.6364). Defined up to
// z = 90 deg (37.92 there); NaN beyond.
double kasten_young_air_mass(double apparent_zenith_deg);

}  // namespace ambisim
