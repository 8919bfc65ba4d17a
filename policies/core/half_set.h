#pragma once
// A coefficient set held as IEEE 754 binary16 bits (54 bytes instead of Sh9Rgb's 108): how a
// planner whose format is fp16 keeps its sets in memory, not only how it rounds them, so that
// the memory it reports is what it holds.
//
// Input ranges: to_half takes any float and rounds as Eigen::half does (to nearest even):
// magnitudes from 65520 up become infinity, those under 2^-14 subnormals or zero.
// half_to_float is exact for every one of the 65536 bit patterns (NaN stays NaN), provided
// subnormal floats are not flushed to zero (no -ffast-math; the test checks every pattern).
#include <array>
#include <bit>
#include <cstdint>

#include "sim/sh/sh9.h"

namespace ambisim {

struct HalfSh9Rgb {
  std::array<std::uint16_t, 3 * kShCount> bits{};  // coefficient k, channel j at 3k + j
};

// The float a binary16 bit pattern stands for. Branch-free for finite values, so that a loop
// over a set vectorises: the exponent and mantissa moved into a float's fields read as the
// value times 2^-112 (a float subnormal for a subnormal half), and one exact multiplication
// by 2^112 puts it right (a normal float); infinities and NaNs get the all-ones float exponent
// instead.
inline float half_to_float(std::uint16_t h) {
  const std::uint32_t magnitude = h & 0x7fffu;
  const std::uint32_t sign = static_cast<std::uint32_t>(h & 0x8000u) << 16;
  const float scaled = std::bit_cast<float>(magnitude << 13) * 0x1p112f;
  // All ones where h is an infinity or a NaN (a mask, not a branch or a select: it vectorises).
  const std::uint32_t special = 0u - static_cast<std::uint32_t>(magnitude >= 0x7c00u);
  const std::uint32_t bits = (std::bit_cast<std::uint32_t>(scaled) & ~special) |
                             (((magnitude << 13) | 0x7f800000u) & special) | sign;
  return std::bit_cast<float>(bits);
}

// The binary16 nearest to f (ties to even).
std::uint16_t float_to_half(float f);

HalfSh9Rgb to_half(const Sh9Rgb& sh);
Sh9Rgb from_half(const HalfSh9Rgb& h);

// sum += h x k, channel by channel (k per channel), without building the float set. The bits
// are decoded in one flat loop first: a loop the compiler vectorises, where decoding inside the
// per-channel product did not (near-probe lookups, 4-5 contributors, took 15 % longer).
inline void sh_add_scaled(Sh9Rgb& sum, const HalfSh9Rgb& h, const Rgb& k) {
  float f[3 * kShCount];
  for (std::size_t i = 0; i < h.bits.size(); ++i) f[i] = half_to_float(h.bits[i]);
  for (int i = 0; i < kShCount; ++i) {
    sum.c[static_cast<std::size_t>(i)] += Rgb(f[3 * i], f[3 * i + 1], f[3 * i + 2]) * k;
  }
}

}  // namespace ambisim
