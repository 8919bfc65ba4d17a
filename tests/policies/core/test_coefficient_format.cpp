// Coefficient storage formats: truncation, fp16 rounding and byte counts.
#include <catch2/catch.hpp>
#include <cmath>

#include "policies/core/coefficient_format.h"

using namespace ambisim;

TEST_CASE("coefficient formats truncate, round and count bytes", "[format]") {
  Sh9Rgb sh;
  for (int k = 0; k < kShCount; ++k) sh.c[k] = Rgb(1.0f + 0.001f * k, -0.3f, 1.0f / 3.0f);
  const CoefficientFormat l2{3, false}, l1{2, false}, l2h{3, true};
  CHECK(l2.store(sh) == sh);
  CHECK(l2.bytes_per_set() == 108);
  CHECK(l1.bytes_per_set() == 48);
  CHECK(l2h.bytes_per_set() == 54);
  const Sh9Rgb t = l1.store(sh);
  CHECK(t.c[3] == sh.c[3]);
  CHECK(t.c[4] == Rgb(0.0f));
  // fp16 has an 11-bit significand: 1/3 rounds to 0.333251953125 (relative error 2.4e-4).
  CHECK(l2h.store(sh).c[0].z == 0.333251953125f);
  CHECK(std::abs(l2h.store(sh).c[8].x - sh.c[8].x) <= std::ldexp(1.0f, -11));
  CHECK(l2h.name() == "L2/fp16");
}
