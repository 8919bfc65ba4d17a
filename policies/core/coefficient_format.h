#pragma once
// How a planner stores coefficients ("model no more than a scene needs"): L1 (4 per channel) or
// L2 (9 per channel), fp32 or fp16. Stored sets go through store(), which truncates and
// rounds exactly as the storage would, so the metrics see the precision a game would get,
// and bytes_per_set() is what the memory statistics count.
#include <cstddef>
#include <string>

#include "policies/core/planner_params.h"
#include "sim/sh/sh9.h"

namespace ambisim {

struct CoefficientFormat {
  int bands = 3;      // 2: L0 + L1 (4 coefficients per channel); 3: L0..L2 (9)
  bool half = false;  // fp16 storage instead of fp32

  int coefficients() const { return bands * bands; }
  std::size_t bytes_per_set() const {
    return static_cast<std::size_t>(coefficients()) * 3 * (half ? 2 : 4);
  }
  // The set as it reads back from storage: bands above `bands` zeroed, values rounded to fp16
  // (round to nearest even, as GPUs convert) when `half`.
  Sh9Rgb store(const Sh9Rgb& sh) const;
  std::string name() const;  // "L2/fp32", "L1/fp16", ...
};

// The two shared planner parameters: "order" (choice "L1" | "L2", default L2) and
// "precision" (choice "fp32" | "fp16", default `default_precision`).
std::vector<ParamSpec> coefficient_format_params(const std::string& default_precision = "fp32");
CoefficientFormat coefficient_format_from(const PlannerParams& params);

}  // namespace ambisim
