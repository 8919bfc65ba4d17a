#include "sim/scenario/speed_profile.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace ambisim {
namespace {

// Below this slope (1/s) a piece is integrated as constant speed: the exact formulas divide
// by g and lose digits there, while the constant-speed error is O(g t^2) < 1e-12 m.
constexpr double kFlatSlope = 1e-12;

}  // namespace

SpeedProfileRecord parse_speed_profile(ObjectReader& r) {
  SpeedProfileRecord rec;
  const bool has_const = r.has("speed_mps");
  const bool has_profile = r.has("speed_profile");
  if (has_const == has_profile) {
    r.fail(has_const ? "speed_profile" : "speed_mps",
           "give exactly one of speed_mps or speed_profile");
  }
  if (has_const) {
    rec.speed_mps = r.number("speed_mps", Range::non_negative());
    return rec;
  }
  auto entries = r.objects("speed_profile");
  if (entries.empty()) r.fail("speed_profile", "needs at least one breakpoint");
  rec.axis = entries[0].has("time_s") ? SpeedProfileRecord::Axis::time
                                      : SpeedProfileRecord::Axis::distance;
  const bool by_time = rec.axis == SpeedProfileRecord::Axis::time;
  const char* key = by_time ? "time_s" : "arc_length_m";
  const char* other = by_time ? "arc_length_m" : "time_s";
  for (auto& e : entries) {
    if (e.has(other)) e.fail(other, std::string("all breakpoints must use ") + key);
    SpeedBreakpoint b;
    b.at = e.number(key, Range::non_negative());
    b.speed_mps = e.number("speed_mps", by_time ? Range::non_negative() : Range::positive());
    if (!rec.points.empty() && !(b.at > rec.points.back().at)) {
      e.fail(key, "must be greater than the previous breakpoint's");
    }
    rec.points.push_back(b);
    e.finish();
  }
  return rec;
}

SpeedProfile::SpeedProfile(SpeedProfileRecord record, double lap_length)
    : axis_(record.axis), lap_(lap_length) {
  using Axis = SpeedProfileRecord::Axis;
  if (axis_ == Axis::constant || record.points.empty()) {
    const double v = record.points.empty() ? record.speed_mps : record.points[0].speed_mps;
    if (axis_ == Axis::constant) axis_ = Axis::time;
    pieces_.push_back({0.0, v, 0.0, 0.0});
  } else {
    const auto& p = record.points;
    // Constant before the first breakpoint, linear between, constant after the last.
    pieces_.push_back({0.0, p[0].speed_mps, 0.0, 0.0});
    for (std::size_t k = 0; k < p.size(); ++k) {
      const double g =
          k + 1 < p.size() ? (p[k + 1].speed_mps - p[k].speed_mps) / (p[k + 1].at - p[k].at) : 0.0;
      Piece piece{p[k].at, p[k].speed_mps, g, integral(p[k].at)};
      if (piece.x0 == pieces_.back().x0)
        pieces_.back() = piece;  // breakpoint at 0
      else
        pieces_.push_back(piece);
    }
  }
  if (axis_ == Axis::distance && lap_ > 0.0) lap_time_ = integral(lap_);
}

const SpeedProfile::Piece& SpeedProfile::piece_at(double x) const {
  auto it = std::upper_bound(pieces_.begin(), pieces_.end(), x,
                             [](double v, const Piece& p) { return v < p.x0; });
  return it == pieces_.begin() ? pieces_.front() : *(it - 1);
}

double SpeedProfile::integral(double x) const {
  const Piece& p = piece_at(x);
  const double d = x - p.x0;
  if (axis_ == SpeedProfileRecord::Axis::time) return p.cum + p.v0 * d + 0.5 * p.g * d * d;
  if (std::abs(p.g) < kFlatSlope) return p.cum + d / p.v0;
  return p.cum + std::log1p(p.g * d / p.v0) / p.g;
}

double SpeedProfile::inverse_integral(double y) const {
  // Pieces are monotone in cum (time increases with distance), so search on cum.
  auto it = std::upper_bound(pieces_.begin(), pieces_.end(), y,
                             [](double v, const Piece& p) { return v < p.cum; });
  const Piece& p = it == pieces_.begin() ? pieces_.front() : *(it - 1);
  const double tau = y - p.cum;
  if (std::abs(p.g) < kFlatSlope) return p.x0 + p.v0 * tau;
  return p.x0 + p.v0 * std::expm1(p.g * tau) / p.g;
}

double SpeedProfile::time_to_reach(double u) const {
  if (lap_ <= 0.0) return integral(u);
  const double laps = std::floor(u / lap_);
  return laps * lap_time_ + integral(u - laps * lap_);
}

double SpeedProfile::distance_at_time(double y) const {
  if (lap_ <= 0.0) return inverse_integral(y);
  const double laps = std::floor(y / lap_time_);
  return laps * lap_ + std::min(inverse_integral(y - laps * lap_time_), lap_);
}

double SpeedProfile::advance(double u0, double t0, double t) const {
  if (axis_ == SpeedProfileRecord::Axis::time) return u0 + (integral(t) - integral(t0));
  return distance_at_time(time_to_reach(u0) + (t - t0));
}

double SpeedProfile::speed(double u, double t) const {
  double x = t;
  if (axis_ == SpeedProfileRecord::Axis::distance) {
    x = lap_ > 0.0 ? u - std::floor(u / lap_) * lap_ : u;
  }
  const Piece& p = piece_at(x);
  return p.v0 + p.g * (x - p.x0);
}

}  // namespace ambisim
