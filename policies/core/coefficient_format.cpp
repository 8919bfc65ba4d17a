#include "policies/core/coefficient_format.h"

#include <Eigen/Core>

namespace ambisim {

Sh9Rgb CoefficientFormat::store(const Sh9Rgb& sh) const {
  Sh9Rgb out = sh_truncate(sh, bands);
  if (half) {
    for (auto& c : out.c) {
      for (int k = 0; k < 3; ++k) c[k] = static_cast<float>(Eigen::half(c[k]));
    }
  }
  return out;
}

std::string CoefficientFormat::name() const {
  return std::string(bands == 2 ? "L1" : "L2") + (half ? "/fp16" : "/fp32");
}

std::vector<ParamSpec> coefficient_format_params(const std::string& default_precision) {
  return {choice_param("order", "L2", {"L1", "L2"},
                       "SH order stored: L1 = 4 coefficients per channel, L2 = 9"),
          choice_param("precision", default_precision, {"fp32", "fp16"},
                       "storage precision of coefficients")};
}

CoefficientFormat coefficient_format_from(const PlannerParams& params) {
  CoefficientFormat f;
  f.bands = params.choice("order") == "L1" ? 2 : 3;
  f.half = params.choice("precision") == "fp16";
  return f;
}

}  // namespace ambisim
