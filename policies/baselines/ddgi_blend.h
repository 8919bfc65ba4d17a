#pragma once
// DDGI's probe blending (RTXGI SDK, rtxgi-sdk/shaders/ddgi/ProbeBlendingCS.hlsl, with the
// defaults of DDGIVolumeDesc in rtxgi-sdk/include/rtxgi/ddgi/DDGIVolume.h), for a probe whose
// input is a full capture instead of a frame's rays. RTXGI per update:
//   h = probeHysteresis (0.97); h = 0 if the probe was black (never lit);
//   if max_rgb |old - new| > probeIrradianceThreshold (0.25): h = max(0, h - 0.75) ("a large
//   lighting change"); delta = new - old;
//   if luminance(delta) > probeBrightnessThreshold (0.10): delta *= 0.25 ("clamp the maximum
//   per-update change in irradiance when a large brightness change is detected");
//   value = old + (1 - h) delta, i.e. lerp(new, old, h).
//
// Here, per update() of dt seconds, towards the probe's latest capture (its target):
//   * Hysteresis applies per frame of a reference rate (60 Hz, since DDGI updates every probe
//     every frame), not per delivered capture: the value moves a fraction 1 - h^(60 dt) of the
//     way, so after t seconds value = target + (start - target) h^(60 t) whatever the frame
//     rate (a time constant of -1 / (60 ln h) = 0.547 s at 0.97). Per delivered capture it
//     would be wrong here: a probe is recaptured seconds apart (noise-free, where DDGI's 0.97
//     averages noisy per-frame rays), and 0.97 per capture takes 33 captures to reach 63 %.
//   * Big change: relative, max_rgb |target - value| / max_rgb |value| of the L0 term above
//     irradiance_threshold, then h - 0.75 (RTXGI's reduction). RTXGI compares absolute values
//     in its gamma-5 encoded [0, 1] irradiance; this simulator's radiometry has no fixed scale,
//     so the relative change is the scale-free equivalent.
//   * Brightness clamp: a brightening step may raise the L0 luminance by at most a fraction
//     brightness_threshold of its current value per reference frame, (1 + c)^(60 dt) - 1 per
//     update. Only brightening, as RTXGI's signed luminance(delta) test (its purpose: bright
//     impulses). A black value (luminance <= 0) is not clamped (RTXGI's h = 0 for black).
//   * A never-captured probe takes its first capture as is (no hysteresis): the caller's job.
#include "sim/sh/sh9.h"

namespace ambisim {

struct DdgiBlendSettings {
  double hysteresis = 0.97;            // probeHysteresis
  double irradiance_threshold = 0.25;  // probeIrradianceThreshold (here relative)
  double brightness_threshold = 0.10;  // probeBrightnessThreshold (here relative, per frame)
  double reference_rate_hz = 60.0;     // DDGI's one update per frame
  static constexpr double kBigChangeReduction = 0.75;  // RTXGI: hysteresis - 0.75
};

// The L0 luminance (Rec. 709 weights) of a set.
float ddgi_luminance(const Sh9Rgb& sh);

// The hysteresis in force for a step from `value` towards `target` (after the big-change rule).
double ddgi_effective_hysteresis(const Sh9Rgb& value, const Sh9Rgb& target,
                                 const DdgiBlendSettings& s);

// The fraction of the way from `value` to `target` one update of dt seconds takes (0: stays,
// 1: jumps), after the hysteresis, the big-change rule and the brightness clamp.
double ddgi_blend_fraction(const Sh9Rgb& value, const Sh9Rgb& target, double dt,
                           const DdgiBlendSettings& s);

}  // namespace ambisim
