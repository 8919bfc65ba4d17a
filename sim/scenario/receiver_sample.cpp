#include "sim/scenario/receiver_sample.h"

#include "sim/base/hash.h"

namespace ambisim {

bool receiver_scored(const ReferenceSettings& settings, const Receiver& r) {
  if (settings.sample_stride <= 1) return true;
  const auto stride = static_cast<std::uint64_t>(settings.sample_stride);
  const std::uint64_t offset =
      hash_combine(settings.sample_seed, static_cast<std::uint64_t>(r.kind)) % stride;
  return (static_cast<std::uint64_t>(r.kind_order) + offset) % stride == 0;
}

}  // namespace ambisim
