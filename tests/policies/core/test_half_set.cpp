// Coefficient sets held as binary16 bits: the branch-free decoding against Eigen::half, the
// reference conversion, for every bit pattern; encoding against CoefficientFormat's rounding.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>

#include <Eigen/Core>

#include "policies/core/coefficient_format.h"
#include "policies/core/half_set.h"

using namespace ambisim;

namespace {

std::uint32_t float_bits(float f) {
  std::uint32_t u = 0;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

}  // namespace

TEST_CASE("half_to_float is exact for every binary16 bit pattern", "[format][half]") {
  int mismatches = 0;
  for (std::uint32_t h = 0; h <= 0xffffu; ++h) {
    const auto bits = static_cast<std::uint16_t>(h);
    const float reference = static_cast<float>(Eigen::numext::bit_cast<Eigen::half>(bits));
    const float fast = half_to_float(bits);
    const bool same =
        std::isnan(reference) ? std::isnan(fast) : float_bits(reference) == float_bits(fast);
    if (!same) ++mismatches;
  }
  CHECK(mismatches == 0);
  // Landmarks: the smallest subnormal, the largest finite, minus zero, infinity.
  CHECK(half_to_float(0x0001u) == std::ldexp(1.0f, -24));
  CHECK(half_to_float(0x7bffu) == 65504.0f);
  CHECK(float_bits(half_to_float(0x8000u)) == 0x80000000u);
  CHECK(std::isinf(half_to_float(0x7c00u)));
}

TEST_CASE("a half set reads back as CoefficientFormat's fp16 rounding", "[format][half]") {
  Sh9Rgb sh;
  for (int k = 0; k < kShCount; ++k) {
    sh.c[static_cast<std::size_t>(k)] = Rgb(1.0f + 0.001f * k, -0.3f * k, 1.0f / (3.0f + k));
  }
  const CoefficientFormat l2h{3, true};
  CHECK(from_half(to_half(sh)) == l2h.store(sh));
  // A stored set survives the round trip bit for bit.
  const Sh9Rgb stored = l2h.store(sh);
  CHECK(from_half(to_half(stored)) == stored);
  // sum += h x k equals the float set's product.
  Sh9Rgb sum, expect;
  const Rgb k(0.5f, 2.0f, -1.25f);
  sh_add_scaled(sum, to_half(sh), k);
  for (int i = 0; i < kShCount; ++i) {
    expect.c[static_cast<std::size_t>(i)] = stored.c[static_cast<std::size_t>(i)] * k;
  }
  CHECK(sum == expect);
}
