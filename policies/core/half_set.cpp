#include "policies/core/half_set.h"

#include <Eigen/Core>

namespace ambisim {

std::uint16_t float_to_half(float f) {
  // Eigen's conversion rounds to nearest even, as GPUs convert (CoefficientFormat::store).
  return Eigen::numext::bit_cast<std::uint16_t>(Eigen::half(f));
}

HalfSh9Rgb to_half(const Sh9Rgb& sh) {
  HalfSh9Rgb h;
  for (int i = 0; i < kShCount; ++i) {
    for (int j = 0; j < 3; ++j) {
      h.bits[static_cast<std::size_t>(3 * i + j)] =
          float_to_half(sh.c[static_cast<std::size_t>(i)][j]);
    }
  }
  return h;
}

Sh9Rgb from_half(const HalfSh9Rgb& h) {
  Sh9Rgb sh;
  for (int i = 0; i < kShCount; ++i) {
    for (int j = 0; j < 3; ++j) {
      sh.c[static_cast<std::size_t>(i)][j] =
          half_to_float(h.bits[static_cast<std::size_t>(3 * i + j)]);
    }
  }
  return sh;
}

}  // namespace ambisim
