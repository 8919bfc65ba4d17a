#pragma once
// Which receivers a sampled referee scores (ReferenceSettings::sample_stride): every k-th of
// each kind in spawn order, starting at an offset per kind drawn from the sample seed. Every
// receiver has the same chance of 1 / k, so the sample's scores estimate the whole
// population's without weights; the kinds and the spawn times are strata (a systematic sample
// spreads over both); a receiver is in or out for its whole life (pops need its consecutive
// frames).
#include "sim/scenario/receivers.h"
#include "sim/scenario/scenario.h"

namespace ambisim {

bool receiver_scored(const ReferenceSettings& settings, const Receiver& r);

// The stratum of a receiver in the sample's intervals (its kind).
inline int receiver_stratum(const Receiver& r) { return static_cast<int>(r.kind); }

}  // namespace ambisim
