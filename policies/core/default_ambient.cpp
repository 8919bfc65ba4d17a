#include "policies/core/default_ambient.h"

#include <limits>

namespace ambisim {

Sh9Rgb hemisphere_sh(const Rgb& sky, const Rgb& ground) {
  constexpr double kPi = 3.14159265358979323846;
  Sh9Rgb sh;
  sh.c[0] = (sky + ground) * static_cast<float>(kShY00 * 2.0 * kPi);
  sh.c[2] = (sky - ground) * static_cast<float>(kPi * kShY1);
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
