#include "sim/metrics/sample_interval.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sim/base/hash.h"

namespace ambisim {
namespace {

struct Ratios {
  double de = 0, de_n = 0, vde = 0, vw = 0, pops = 0, s = 0, vpop = 0, vs = 0;
  void add(const ReceiverTotals& r) {
    de += r.de_sum;
    de_n += static_cast<double>(r.samples);
    vde += r.viewed_de_sum;
    vw += r.viewed_weight;
    pops += static_cast<double>(r.pops);
    s += r.seconds;
    vpop += r.viewed_pop_weight;
    vs += r.viewed_seconds;
  }
};

double ratio(double a, double b) {
  return b > 0.0 ? a / b : std::numeric_limits<double>::quiet_NaN();
}

Interval percentile_interval(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  Interval out{kNoInterval, kNoInterval};
  if (v.size() < 2) return out;
  std::sort(v.begin(), v.end());
  auto at = [&](double q) {
    const double pos = q * static_cast<double>(v.size() - 1);
    const auto i = static_cast<std::size_t>(std::floor(pos));
    const double f = pos - static_cast<double>(i);
    return i + 1 < v.size() ? v[i] * (1.0 - f) + v[i + 1] * f : v[i];
  };
  out.low = at(0.025);
  out.high = at(0.975);
  return out;
}

}  // namespace

SampleIntervals bootstrap_intervals(std::span<const ReceiverTotals> receivers, int replicates,
                                    std::uint64_t seed) {
  if (replicates < 20) throw std::invalid_argument("bootstrap_intervals: replicates must be >= 20");
  std::map<int, std::vector<const ReceiverTotals*>> strata;
  for (const auto& r : receivers) strata[r.stratum].push_back(&r);
  bool any = false;
  for (const auto& [h, members] : strata) any |= members.size() >= 2;
  if (!any) return {};
  std::vector<double> de, vde, pops, vpops;
  for (int b = 0; b < replicates; ++b) {
    Ratios t;
    for (const auto& [h, members] : strata) {
      const std::uint64_t n = members.size();
      for (std::uint64_t k = 0; k < n; ++k) {
        const std::uint64_t u =
            hash_combine(hash_combine(hash_combine(seed, static_cast<std::uint64_t>(b)),
                                      static_cast<std::uint64_t>(h)),
                         k);
        t.add(*members[u % n]);
      }
    }
    de.push_back(ratio(t.de, t.de_n));
    vde.push_back(ratio(t.vde, t.vw));
    pops.push_back(ratio(t.pops, t.s / 60.0));
    vpops.push_back(ratio(t.vpop, t.vs / 60.0));
  }
  return {percentile_interval(de), percentile_interval(vde), percentile_interval(pops),
          percentile_interval(vpops)};
}

ReceiverTotals& ReceiverTally::at(std::uint64_t id, int stratum) {
  auto [it, inserted] = by_id_.try_emplace(id);
  if (inserted) it->second.stratum = stratum;
  return it->second;
}

std::vector<ReceiverTotals> ReceiverTally::totals() const {
  std::vector<ReceiverTotals> out;
  out.reserve(by_id_.size());
  for (const auto& [id, t] : by_id_) out.push_back(t);
  return out;
}

}  // namespace ambisim
