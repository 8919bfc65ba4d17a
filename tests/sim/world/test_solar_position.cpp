// The sun's position against published values: NOAA's own spreadsheet (its stored results, to
// 1e-9), NREL's SPA example (an independent algorithm, to NOAA's accuracy), and Kasten & Young's
// air mass.
#include <catch2/catch.hpp>
#include <cmath>

#include "sim/world/solar_position.h"

using namespace ambisim;

namespace {

constexpr double kSheetTol = 1e-9;  // NOAA_Solar_Calculations_day.xls, stored results
constexpr double kSpaTol = 0.01;    // NOAA's algorithm against NREL SPA, deg

// The spreadsheet's default place: 40 N, 105 W, UTC-6, 2010-06-21.
SolarPosition sheet(double hours) {
  return noaa_solar_position(2010, 6, 21, hours * 60.0, 40.0, -105.0, -6.0);
}

}  // namespace

TEST_CASE("NOAA solar position: every intermediate of the spreadsheet at 06:00, 12:00, 18:00",
          "[world][sun]") {
  struct Row {
    double hours;
    double jd, jc, l0, m, e, c, true_long, true_anom, r, app_long, eps0, eps, ra, dec, y, eot;
    double ha_rise, noon, rise, set, tst, ha, zenith, elev, refr, app_elev, az;
  };
  // Table "A" of the stored results (17 significant digits as stored).
  const Row rows[] = {{6.0,
                       2455369.0000000000,
                       0.10469541409993155,
                       89.581968591586701,
                       4126.4645856310854,
                       0.016704231530102344,
                       0.43908178144809601,
                       90.021050373034797,
                       4126.9036674125337,
                       1.0162562337927736,
                       90.020026257021769,
                       23.437929633278447,
                       23.438485674088472,
                       90.021827276679758,
                       23.438484156784963,
                       0.043031487632765188,
                       -1.7597485510968045,
                       112.61053377111881,
                       0.54288871427159502,
                       0.23008167601848722,
                       0.85569575252470287,
                       298.24025144890368,
                       -105.43993713777408,
                       86.068535435399667,
                       3.9314645646003328,
                       0.19126809017452331,
                       4.1227326547748557,
                       62.431931240159258},
                      {12.0,
                       2455369.2500000000,
                       0.10470225872689938,
                       89.828380432062204,
                       4126.7109857012965,
                       0.016704231242193168,
                       0.43122524980095422,
                       90.259605681863164,
                       4127.1422109510977,
                       1.0162723674182423,
                       90.258581805613716,
                       23.437929544269654,
                       23.438485007686928,
                       90.281836462086773,
                       23.438232038479374,
                       0.043031485116224510,
                       -1.8140623431998828,
                       112.61025908393994,
                       0.54292643218277759,
                       0.23012015694961108,
                       0.85573270741594409,
                       658.18593765679930,
                       -15.453515585800176,
                       21.076156288836351,
                       68.923843711163642,
                       0.0062186511507711720,
                       68.930062362314416,
                       137.16999990870255},
                      {18.0,
                       2455369.5000000000,
                       0.10470910335386721,
                       90.074792272537707,
                       4126.9573857715068,
                       0.016704230954283979,
                       0.42336121187905390,
                       90.498153484416761,
                       4127.3807469833855,
                       1.0162882094249306,
                       90.497129847681776,
                       23.437929455260864,
                       23.438484341255737,
                       90.541835626844261,
                       23.437549348407504,
                       0.043031482599571950,
                       -1.8683370541473712,
                       112.60951528964290,
                       0.54296412295426899,
                       0.23015991381637202,
                       0.85576833209216596,
                       1018.1316629458506,
                       74.532915736462655,
                       63.697817037244477,
                       26.302182962755523,
                       0.032491217491637921,
                       26.334674180247163,
                       279.46469179006533}};
  for (const Row& w : rows) {
    const SolarPosition s = sheet(w.hours);
    CAPTURE(w.hours);
    CHECK(s.julian_day == Approx(w.jd).margin(kSheetTol));
    CHECK(s.julian_century == Approx(w.jc).margin(kSheetTol));
    CHECK(s.geom_mean_long_deg == Approx(w.l0).margin(kSheetTol));
    CHECK(s.geom_mean_anom_deg == Approx(w.m).margin(kSheetTol));
    CHECK(s.eccentricity == Approx(w.e).margin(kSheetTol));
    CHECK(s.eq_of_centre_deg == Approx(w.c).margin(kSheetTol));
    CHECK(s.true_long_deg == Approx(w.true_long).margin(kSheetTol));
    CHECK(s.true_anom_deg == Approx(w.true_anom).margin(kSheetTol));
    CHECK(s.radius_au == Approx(w.r).margin(kSheetTol));
    CHECK(s.apparent_long_deg == Approx(w.app_long).margin(kSheetTol));
    CHECK(s.mean_obliquity_deg == Approx(w.eps0).margin(kSheetTol));
    CHECK(s.obliquity_deg == Approx(w.eps).margin(kSheetTol));
    CHECK(s.right_ascension_deg == Approx(w.ra).margin(kSheetTol));
    CHECK(s.declination_deg == Approx(w.dec).margin(kSheetTol));
    CHECK(s.var_y == Approx(w.y).margin(kSheetTol));
    CHECK(s.equation_of_time_min == Approx(w.eot).margin(kSheetTol));
    CHECK(s.hour_angle_sunrise_deg == Approx(w.ha_rise).margin(kSheetTol));
    CHECK(s.solar_noon_day == Approx(w.noon).margin(kSheetTol));
    CHECK(s.sunrise_day == Approx(w.rise).margin(kSheetTol));
    CHECK(s.sunset_day == Approx(w.set).margin(kSheetTol));
    CHECK(s.true_solar_time_min == Approx(w.tst).margin(kSheetTol));
    CHECK(s.hour_angle_deg == Approx(w.ha).margin(kSheetTol));
    CHECK(s.zenith_deg == Approx(w.zenith).margin(kSheetTol));
    CHECK(s.elevation_deg == Approx(w.elev).margin(kSheetTol));
    CHECK(s.refraction_deg == Approx(w.refr).margin(kSheetTol));
    CHECK(s.apparent_elevation_deg == Approx(w.app_elev).margin(kSheetTol));
    CHECK(s.azimuth_deg == Approx(w.az).margin(kSheetTol));
  }
}

TEST_CASE("NOAA solar position: the spreadsheet's hourly table, night included", "[world][sun]") {
  struct Row {
    double hours, dec, eot, ha, zenith, app_elev, az;
  };
  const Row rows[] = {{1, 23.438365311626107, -1.7144616390637752, 179.57138459023406,
                       116.56037496504590, -26.548832610060181, 359.56035118968396},
                      {3, 23.438448736191415, -1.7325789206478697, -150.43314473016198,
                       110.83242557781352, -20.817261802482243, 28.972608339537601},
                      {5, 23.438484311850726, -1.7506928845202161, -120.43767322112997,
                       95.761024500792743, -5.7038329756326664, 52.660531721490088},
                      {9, 23.438411922336620, -1.7869099481135473, -60.446727487028426,
                       52.962388955228086, 37.058953690134899, 89.007964883243289},
                      {13, 23.438148156172851, -1.8231110082879149, -0.45577775207223681,
                       16.566321028125600, 73.438479343962641, 178.53323003787727},
                      {17, 23.437693028556001, -1.8592942438254636, 59.535176439043170,
                       52.264551508753641, 37.756261225782346, 270.41187629584522},
                      {21, 23.437046556795700, -1.8954578336297214, 119.52613554159188,
                       95.204615831187098, -5.1412707441521421, 306.71221184242910},
                      {23, 23.436651572845129, -1.9135316925781294, 149.52161707685468,
                       110.49148396072920, -20.476044399303145, 330.21122122833106}};
  for (const Row& w : rows) {
    const SolarPosition s = sheet(w.hours);
    CAPTURE(w.hours);
    CHECK(s.declination_deg == Approx(w.dec).margin(kSheetTol));
    CHECK(s.equation_of_time_min == Approx(w.eot).margin(kSheetTol));
    CHECK(s.hour_angle_deg == Approx(w.ha).margin(kSheetTol));
    CHECK(s.zenith_deg == Approx(w.zenith).margin(kSheetTol));
    CHECK(s.apparent_elevation_deg == Approx(w.app_elev).margin(kSheetTol));
    CHECK(s.azimuth_deg == Approx(w.az).margin(kSheetTol));
  }
}

TEST_CASE("NOAA solar position: the year sheet's noon values across 2010", "[world][sun]") {
  struct Row {
    int month, day;
    double dec, eot, zenith, az;
  };
  // 12:00 local standard time, 40 N, 105 W, UTC-7.
  const Row rows[] = {
      {1, 1, -22.961508129687317, -3.6859645773235221, 62.967376002248862, 179.04745069279693},
      {3, 20, 0.024868338240887116, -7.3944312788808162, 40.010674313181511, 177.12400663546282},
      {9, 23, -0.25671373542151743, 7.6811570557098454, 40.294841652617052, 182.97001372893499},
      {11, 3, -15.205105804481963, 16.476857921125507, 55.338233451183058, 184.83427560785879},
      {12, 21, -23.437849317137342, 1.8015641669267379, 63.439240301631550, 180.46198836770978}};
  for (const Row& w : rows) {
    const SolarPosition s = noaa_solar_position(2010, w.month, w.day, 720.0, 40.0, -105.0, -7.0);
    CAPTURE(w.month, w.day);
    CHECK(s.declination_deg == Approx(w.dec).margin(kSheetTol));
    CHECK(s.equation_of_time_min == Approx(w.eot).margin(kSheetTol));
    CHECK(s.zenith_deg == Approx(w.zenith).margin(kSheetTol));
    CHECK(s.azimuth_deg == Approx(w.az).margin(kSheetTol));
  }
}

TEST_CASE("NOAA solar position against NREL SPA's example (Reda & Andreas 2008)", "[world][sun]") {
  // 2003-10-17 12:30:30 local, UTC-7, Golden CO. SPA: geometric (topocentric) elevation
  // 39.872046 deg, azimuth 194.340241 deg, declination -9.31434 deg, EoT 14.64 min. NOAA has no
  // pressure term in its refraction, so the geometric angles are compared.
  const SolarPosition s =
      noaa_solar_position(2003, 10, 17, 12 * 60 + 30.5, 39.742476, -105.1786, -7.0);
  CHECK(s.elevation_deg == Approx(39.872046).margin(kSpaTol));
  CHECK(s.azimuth_deg == Approx(194.340241).margin(kSpaTol));
  CHECK(s.declination_deg == Approx(-9.31434).margin(0.005));
  CHECK(s.equation_of_time_min == Approx(14.64).margin(0.02));
  // The next day: elevation 39.505196, azimuth 194.311132 (NREL SPA web calculator).
  const SolarPosition n =
      noaa_solar_position(2003, 10, 18, 12 * 60 + 30.5, 39.742476, -105.1786, -7.0);
  CHECK(n.elevation_deg == Approx(39.505196).margin(kSpaTol));
  CHECK(n.azimuth_deg == Approx(194.311132).margin(kSpaTol));
}

TEST_CASE("refraction: zero above 85 deg, the three branches below", "[world][sun]") {
  CHECK(noaa_refraction_deg(86.0) == 0.0);
  // The spreadsheet's 00:06 row: h = -25.245718494866011 gives 0.012236520519362753.
  CHECK(noaa_refraction_deg(-25.245718494866011) == Approx(0.012236520519362753).margin(1e-12));
  // At the horizon the polynomial: 1735 arc seconds.
  CHECK(noaa_refraction_deg(0.0) == Approx(1735.0 / 3600.0).margin(1e-15));
}

TEST_CASE("air mass: Kasten & Young 1989", "[world][sun]") {
  // The formula's values (computed to 1e-6 relative) and pvlib's published test values.
  CHECK(kasten_young_air_mass(0.0) == Approx(0.999712).epsilon(1e-6));
  CHECK(kasten_young_air_mass(60.0) == Approx(1.994293).epsilon(1e-6));
  CHECK(kasten_young_air_mass(85.0) == Approx(10.305791).epsilon(1e-6));
  CHECK(kasten_young_air_mass(90.0) == Approx(37.919608).epsilon(1e-6));
  CHECK(kasten_young_air_mass(89.9) == Approx(36.467).margin(1e-3));
  CHECK(kasten_young_air_mass(80.0) == Approx(5.586).margin(1e-3));
  CHECK(std::isnan(kasten_young_air_mass(100.0)));
}
