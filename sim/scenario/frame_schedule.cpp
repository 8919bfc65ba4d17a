#include "sim/scenario/frame_schedule.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace ambisim {
namespace {

constexpr double kMaxFps = 10000.0;
constexpr double kMaxDuration = 86400.0;  // s: one day
// Every frame keeps a row of per-frame series and reference samples: beyond this a run is a
// mistake (1e6 frames: 4.6 h at 60 fps), not a simulation, and is refused before it starts.
constexpr std::int64_t kMaxFrames = 1000000;

}  // namespace

FrameScheduleRecord parse_frame_schedule(ObjectReader& r) {
  FrameScheduleRecord rec;
  rec.duration_s = r.number("duration_s", 10.0, {0.0, kMaxDuration, true, false});
  if (r.has("fps") && r.has("segments")) r.fail("segments", "give fps or segments, not both");
  if (r.has("segments")) {
    auto entries = r.objects("segments");
    if (entries.empty()) r.fail("segments", "needs at least one segment");
    for (auto& e : entries) {
      FpsSegment s;
      s.from_s = e.number("from_s", Range::non_negative());
      s.fps = e.number("fps", {0.0, kMaxFps, true, false});
      s.ramp_to_next = e.boolean("ramp_to_next", false);
      if (rec.segments.empty() && s.from_s != 0.0)
        e.fail("from_s", "the first segment must start at 0");
      if (!rec.segments.empty() && !(s.from_s > rec.segments.back().from_s)) {
        e.fail("from_s", "must be greater than the previous segment's");
      }
      rec.segments.push_back(s);
      e.finish();
    }
    if (rec.segments.back().ramp_to_next) {
      entries.back().fail("ramp_to_next", "the last segment has no next segment to ramp to");
    }
  } else {
    rec.segments.push_back({0.0, r.number("fps", 60.0, {0.0, kMaxFps, true, false}), false});
  }
  r.finish();
  const std::int64_t frames = FrameSchedule(rec).frame_count();
  if (frames > kMaxFrames) {
    r.fail("duration_s", "gives " + std::to_string(frames) +
                             " frames at this frame rate; at most " + std::to_string(kMaxFrames));
  }
  return rec;
}

FrameSchedule::FrameSchedule(FrameScheduleRecord record) : duration_(record.duration_s) {
  const auto& seg = record.segments;
  if (seg.empty() || seg[0].from_s != 0.0) throw std::invalid_argument("bad frame schedule");
  double n = 0.0;
  for (std::size_t i = 0; i < seg.size(); ++i) {
    const bool last = i + 1 == seg.size();
    const double t1 = last ? std::numeric_limits<double>::infinity() : seg[i + 1].from_s;
    const double g =
        !last && seg[i].ramp_to_next ? (seg[i + 1].fps - seg[i].fps) / (t1 - seg[i].from_s) : 0.0;
    pieces_.push_back({seg[i].from_s, t1, seg[i].fps, g, n});
    if (!last) n += (seg[i].fps + 0.5 * g * (t1 - seg[i].from_s)) * (t1 - seg[i].from_s);
  }
  // Frames at times < duration: k < N(duration), up to rounding of N, which time_of settles.
  count_ = static_cast<std::int64_t>(std::ceil(frames_before(duration_)));
  while (count_ > 0 && time_of(count_ - 1) >= duration_) --count_;
  while (time_of(count_) < duration_) ++count_;
}

double FrameSchedule::fps_at(double t) const {
  auto it = std::upper_bound(pieces_.begin(), pieces_.end(), t,
                             [](double v, const Piece& p) { return v < p.t0; });
  const Piece& p = it == pieces_.begin() ? pieces_.front() : *(it - 1);
  return p.f0 + p.g * (t - p.t0);
}

double FrameSchedule::frames_before(double t) const {
  auto it = std::upper_bound(pieces_.begin(), pieces_.end(), t,
                             [](double v, const Piece& p) { return v < p.t0; });
  const Piece& p = it == pieces_.begin() ? pieces_.front() : *(it - 1);
  const double d = t - p.t0;
  return p.n0 + (p.f0 + 0.5 * p.g * d) * d;
}

double FrameSchedule::time_of(std::int64_t k) const {
  const double kk = static_cast<double>(k);
  auto it = std::upper_bound(pieces_.begin(), pieces_.end(), kk,
                             [](double v, const Piece& p) { return v < p.n0; });
  const Piece& p = it == pieces_.begin() ? pieces_.front() : *(it - 1);
  const double m = kk - p.n0;  // frames into this piece
  if (p.g == 0.0) return p.t0 + m / p.f0;
  // Root of f0 d + g d^2 / 2 = m in the cancellation-free form (fps stays > 0 on a ramp).
  return p.t0 + 2.0 * m / (p.f0 + std::sqrt(std::max(p.f0 * p.f0 + 2.0 * p.g * m, 0.0)));
}

Frame FrameSchedule::frame(std::int64_t k) const {
  Frame f;
  f.index = k;
  f.time = time_of(k);
  f.dt = k == 0 ? 1.0 / fps_at(0.0) : f.time - time_of(k - 1);
  return f;
}

bool FrameClock::next(Frame& out) {
  if (k_ >= schedule_->frame_count()) return false;
  out = schedule_->frame(k_++);
  return true;
}

}  // namespace ambisim
