#include "policies/thesis/coefficient_anchor.h"

#include <algorithm>

namespace ambisim {

void CoefficientAnchor::set_new(const Sh9Rgb& sh, double creation_time, std::uint64_t tag,
                                const Sh9Rgb* fade_from, double fade_from_time) {
  if (!has_) {
    // A fresh anchor: fade from what lookups showed here, or snap in when nothing did.
    active_ = fade_from ? *fade_from : sh;
    data_time_ = fade_from ? fade_from_time : creation_time;
  }
  if (new_) {
    *new_ = sh;
  } else {
    new_ = std::make_unique<Sh9Rgb>(sh);
  }
  creation_time_ = creation_time;
  tag_ = tag;
  has_ = true;
  in_flight_ = false;
  need_new_ = false;
  fading_ = true;
  fade_pending_ = true;
}

bool CoefficientAnchor::update(double now, const AnchorTiming& timing) {
  if (fading_) {
    if (fade_pending_) {
      fade_pending_ = false;
      fade_last_ = now;
      fade_end_ = now + timing.fade_s;
    }
    if (now >= fade_end_) {
      active_ = *new_;
      new_.reset();
      data_time_ = creation_time_;
      fading_ = false;
    } else if (now > fade_last_) {
      // One linear step: moving the remaining fraction dt / (end - last) keeps Active on the
      // straight line from its value at the fade start to New, with only two sets stored.
      const double f = (now - fade_last_) / (fade_end_ - fade_last_);
      active_ = sh_lerp(active_, *new_, static_cast<float>(f));
      data_time_ += f * (creation_time_ - data_time_);
      fade_last_ = now;
    }
  }
  if (!has_) return false;
  const double age = now - creation_time_;
  const double limit = timing.lifetime_s + (in_flight_ ? timing.fade_s : 0.0);
  if (age > limit) {
    has_ = false;
    need_new_ = false;
    fading_ = false;
    fade_pending_ = false;
    new_.reset();
    return true;
  }
  const double renewal_age = timing.clock != nullptr ? timing.clock->age(creation_time_) : age;
  need_new_ = !in_flight_ && renewal_age > timing.lifetime_s - timing.margin_s;
  return false;
}

}  // namespace ambisim
