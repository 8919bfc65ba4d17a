#include "policies/core/default_ambient.h"

#include <limits>
#include <numbers>

namespace ambisim {

Sh9Rgb hemisphere_sh(const Rgb& sky, const Rgb& ground) {
  Sh9Rgb sh;
  sh.c[0] = (sky + ground) * static_cast<float>(kShY00 * 2.0 * std::numbers::pi);
  sh.c[2] = (sky - ground) * static_cast<float>(std::numbers::pi * kShY1);
  return sh;
}

const Sh9Rgb& default_ambient_sh() {
  static const Sh9Rgb sh = hemisphere_sh(Rgb(kDefaultSkyRadiance), Rgb(kDefaultGroundRadiance));
  return sh;
}

LookupResult default_ambient_lookup() {
  LookupResult r;
  r.sh = default_ambient_sh();
  r.fell_back = true;
  r.spacing_m = std::numeric_limits<double>::infinity();
  return r;
}

}  // namespace ambisim
