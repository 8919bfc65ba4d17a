#include "sim/scenario/capture_budget.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ambisim {
namespace {

constexpr double kMaxFaces = 96.0;  // 16 probes per frame: far beyond any real engine
// A credit within this of a whole number is that number: ten frames of 0.1 sum to
// 0.9999999999999999 in binary, which must still yield a face on the tenth frame.
constexpr double kSnap = 1e-9;

}  // namespace

CaptureBudgetRecord parse_capture_budget(ObjectReader& r) {
  CaptureBudgetRecord rec;
  if (r.has("faces_per_frame") && r.has("schedule")) {
    r.fail("schedule", "give faces_per_frame or schedule, not both");
  }
  rec.faces_per_frame = r.number("faces_per_frame", 1.0, Range::closed(0.0, kMaxFaces));
  if (r.has("schedule")) {
    auto entries = r.objects("schedule");
    if (entries.empty()) r.fail("schedule", "needs at least one step");
    for (auto& e : entries) {
      BudgetStep s;
      s.from_s = e.number("from_s", Range::non_negative());
      s.faces_per_frame = e.number("faces_per_frame", Range::closed(0.0, kMaxFaces));
      if (rec.schedule.empty() && s.from_s != 0.0)
        e.fail("from_s", "the first step must start at 0");
      if (!rec.schedule.empty() && !(s.from_s > rec.schedule.back().from_s)) {
        e.fail("from_s", "must be greater than the previous step's");
      }
      rec.schedule.push_back(s);
      e.finish();
    }
  }
  rec.face_size = r.integer("face_size", 16, Range::closed(1, 1024));
  rec.max_carry_faces = r.integer("max_carry_faces", 0, Range::closed(0, kMaxFaces));
  r.finish();
  return rec;
}

CaptureBudget::CaptureBudget(CaptureBudgetRecord record)
    : schedule_(std::move(record.schedule)),
      face_size_(record.face_size),
      max_carry_(record.max_carry_faces) {
  if (schedule_.empty()) schedule_.push_back({0.0, record.faces_per_frame});
  if (face_size_ < 1 || max_carry_ < 0) throw std::invalid_argument("bad capture budget");
}

double CaptureBudget::faces_per_frame(double time) const {
  auto it = std::upper_bound(schedule_.begin(), schedule_.end(), time,
                             [](double t, const BudgetStep& s) { return t < s.from_s; });
  return (it == schedule_.begin() ? schedule_.front() : *(it - 1)).faces_per_frame;
}

void CaptureBudget::begin_frame(double time) {
  const double whole = std::floor(credit_);
  credit_ = (credit_ - whole) + std::min(whole, static_cast<double>(max_carry_));
  credit_ += faces_per_frame(time);
  const double nearest = std::round(credit_);
  if (std::abs(credit_ - nearest) < kSnap) credit_ = nearest;
  ++counters_.frames;
}

int CaptureBudget::available() const { return static_cast<int>(std::floor(credit_)); }

int CaptureBudget::grant(int requested) {
  requested = std::max(requested, 0);
  const int g = std::min(requested, available());
  credit_ -= g;
  counters_.requested += requested;
  counters_.granted += g;
  counters_.refused += requested - g;
  return g;
}

}  // namespace ambisim
