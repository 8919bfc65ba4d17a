#pragma once
// How fast something moves along a course: a constant, or speed breakpoints over time or over
// distance travelled, interpolated linearly and held constant beyond the first and last
// breakpoint. Distance at a time is integrated in closed form (no step-size error):
//   speed linear in time     -> distance is quadratic in time on each piece;
//   speed linear in distance -> ds/dt = v0 + g s gives s = v0 (e^{g t} - 1) / g.
#include <vector>

#include "sim/base/json_reader.h"

namespace ambisim {

struct SpeedBreakpoint {
  double at = 0.0;         // time_s (s) or arc_length_m (m), by the profile's axis
  double speed_mps = 0.0;  // m/s
};

struct SpeedProfileRecord {
  enum class Axis { constant, time, distance };
  Axis axis = Axis::constant;
  double speed_mps = 0.0;               // Axis::constant only
  std::vector<SpeedBreakpoint> points;  // strictly increasing `at`
};

// Reads from the enclosing object exactly one of
//   "speed_mps": m/s >= 0, or
//   "speed_profile": [{"time_s": s >= 0, "speed_mps": m/s >= 0}, ...]   (speed over time), or
//   "speed_profile": [{"arc_length_m": m >= 0, "speed_mps": m/s > 0}, ...] (speed over distance
//     travelled along the course; > 0 because a zero-speed point would never be reached).
// Entries must share one axis, with strictly increasing time_s / arc_length_m.
SpeedProfileRecord parse_speed_profile(ObjectReader& r);

class SpeedProfile {
 public:
  // `lap_length` > 0 repeats a distance profile every lap (a looping course); 0 = no repeat.
  explicit SpeedProfile(SpeedProfileRecord record, double lap_length = 0.0);

  // Distance coordinate at time t >= t0 of something that was at u0 >= 0 at time t0 >= 0.
  double advance(double u0, double t0, double t) const;
  // Speed (m/s) at time t (time axis) or at distance u (distance axis).
  double speed(double u, double t) const;

 private:
  // One linear piece: speed v0 + g x over x in [x0, next x0); `cum` is the integral up to x0
  // (distance for the time axis, time for the distance axis).
  struct Piece {
    double x0, v0, g, cum;
  };
  const Piece& piece_at(double x) const;
  double integral(double x) const;          // distance by time, or time to reach distance
  double inverse_integral(double y) const;  // distance axis only: distance reached at time y
  double time_to_reach(double u) const;     // distance axis, with laps
  double distance_at_time(double y) const;  // distance axis, with laps

  SpeedProfileRecord::Axis axis_;
  std::vector<Piece> pieces_;
  double lap_ = 0.0;
  double lap_time_ = 0.0;
};

}  // namespace ambisim
