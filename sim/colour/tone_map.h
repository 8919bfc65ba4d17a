#pragma once
// Display mapping of linear HDR colour (seed 003, section 3.2; Reinhard et al. 2002): a fixed
// exposure, then the global Reinhard curve L / (1 + L) on luminance, then sRGB for display and
// CIELAB for perceptual metrics (CIEDE2000).
//
// Choosing the exposure (per scenario, fixed for the whole run so colours stay comparable
// between frames and planners): Reinhard's key value, exposure = key / L_avg, with key = 0.18
// (middle grey) and L_avg the log-average luminance (seed 003 eq. 3.2) of the *reference*
// displayed quantity over the scenario, e.g. all receivers' reference irradiance over all
// frames and normals. It must come from the reference, never from a planner's output, or the
// metric would reward planners for changing their own exposure. See exposure_for_key().
#include <array>
#include <cstdint>
#include <span>

#include "sim/colour/cielab.h"
#include "sim/colour/rgb.h"

namespace ambisim {

inline constexpr double kMiddleGreyKey = 0.18;

// Log-average luminance exp(mean(log(delta + Y))) of linear colours (seed 003 eq. 3.2). Negative
// components (SH ringing) count as 0; delta > 0 keeps black samples finite. Empty input -> 0.
double log_average_luminance(std::span<const Rgb> linear, double delta = 1e-4);

// Exposure multiplier that maps a scene of log-average luminance `log_avg` (> 0) to `key`.
double exposure_for_key(double log_avg, double key = kMiddleGreyKey);

// Global Reinhard on luminance with the colour ratios kept:
//   c = max(linear, 0) * exposure,  Y = luminance(c),  out = c * (Y / (1 + Y)) / Y.
// Why luminance and not per channel: per-channel x / (1 + x) compresses a bright channel more
// than a dim one, which shifts hue (a saturated orange (4, 1, 0) becomes (0.8, 0.5, 0), a
// yellower orange) and washes bright colour pops toward white; keeping the ratios keeps hue and
// chromaticity, so a colour pop stays a colour pop. A saturated colour can then exceed 1 in one
// channel (pure blue has Y = 0.072 of its blue value); it is scaled down by its largest channel,
// which again keeps the ratios (hue) and only lowers brightness.
// Input: linear RGB (negatives treated as 0), exposure >= 0. Output: display-linear [0, 1]^3.
Rgb tone_map_reinhard(Rgb linear, double exposure);

// The displayed colour in CIELAB: tone map -> clamp to [0, 1] -> linear sRGB -> XYZ -> Lab.
Lab display_lab(Rgb linear, double exposure);

// The displayed colour as 8-bit sRGB: tone map -> sRGB OETF -> round to 8 bits.
std::array<std::uint8_t, 3> to_srgb8(Rgb linear, double exposure);

}  // namespace ambisim
