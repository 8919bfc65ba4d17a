#pragma once
// CoefficientAnchor (thesis Bilaga B, L977-981): one coefficient set's life at one position.
// It holds the set lookups read (Active) and the newest capture (New), whether a capture for
// it is in flight, and when its data was captured. New data fades in linearly over fade_s
// (D8) from whatever Active was: for a replacement that is the old set, for a fresh anchor the
// value lookups gave here just before arrival (or a snap when there was none). It asks for a
// replacement lifetime - margin after capture (D7; sooner under changing light, AnchorTiming),
// serves the old set while the replacement is in flight until lifetime + fade_s, and loses its
// set after that. It is passive: update()
// only reports the loss, the graph decides what it means for its owners.
//
// New is needed only while a fade runs (when it ends, Active is New), so it lives on the heap
// for that second and a fraction: an anchor holds one set, not two, for the other 59 s of its
// lifetime (thesis Bilaga B keeps both for ever; issue 15's memory target).
#include <cstdint>
#include <memory>

#include "policies/core/light_clock.h"
#include "sim/sh/sh9.h"

namespace ambisim {

struct AnchorTiming {
  double lifetime_s = 60.0;  // validity of a set, from its request time (D6)
  double fade_s = 1.0;       // linear fade-in of new coefficients (D8)
  double margin_s = 1.0;     // re-request this long before the lifetime ends (D7)
  // Renewal on the light clock (the thesis' refresh rule, light_clock.h; null: real time): a
  // set asks for its replacement at clock age lifetime - margin (margin_s then in clock
  // seconds), so sooner while the light changes. It is still lost only at real age lifetime
  // (+ fade_s while its replacement is in flight): a stale set serves better than none.
  const LightClock* clock = nullptr;
};

class CoefficientAnchor {
 public:
  bool has_coefficients() const { return has_; }
  bool in_flight() const { return in_flight_; }
  bool need_new() const { return need_new_; }
  bool fading() const { return fading_; }
  double creation_time() const { return creation_time_; }  // of the newest set
  // The (weighted) capture time of what lookups see: mid-fade it moves from the old set's time.
  double data_time() const { return data_time_; }
  std::uint64_t tag() const { return tag_; }  // the capture whose data is the newest
  const Sh9Rgb& active() const { return active_; }
  // Whether New is held (exactly while fading): what the memory statistics count beside Active.
  bool holds_new() const { return new_ != nullptr; }

  // PrepareForNewCoefficients / a refused or lost capture.
  void prepare_for_new() { in_flight_ = true; }
  void cancel_request() { in_flight_ = false; }

  // SetNewCoefficients. `fade_from`: for an anchor without coefficients, the value lookups
  // returned here just before (null: the set snaps in). The fade starts at the next update(),
  // the first moment the set is usable, so lookups in that frame still see the old value.
  void set_new(const Sh9Rgb& sh, double creation_time, std::uint64_t tag, const Sh9Rgb* fade_from,
               double fade_from_time);

  // Fades, re-request flag, expiry. Returns true when the anchor lost its set this call.
  bool update(double now, const AnchorTiming& timing);

 private:
  Sh9Rgb active_;
  std::unique_ptr<Sh9Rgb> new_;  // only while fading
  double creation_time_ = 0.0;
  double data_time_ = 0.0;
  double fade_last_ = 0.0;  // time of the last fade step
  double fade_end_ = 0.0;
  std::uint64_t tag_ = 0;
  bool has_ = false;
  bool in_flight_ = false;
  bool need_new_ = false;
  bool fading_ = false;
  bool fade_pending_ = false;  // delivered, fade starts at the next update
};

}  // namespace ambisim
