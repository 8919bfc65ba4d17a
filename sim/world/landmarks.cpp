#include "sim/world/landmarks.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace ambisim {
namespace {

bool is_open(Biome b) { return b == Biome::Grass || b == Biome::Field || b == Biome::Sand; }

ForestEdgeApproach find_forest_edge(const World& w) {
  ForestEdgeApproach best;
  const glm::dvec2 lo = w.min_xy() + glm::dvec2(200.0), hi = w.max_xy() - glm::dvec2(200.0);
  constexpr double kGrid = 32.0, kStep = 4.0, kMaxRun = 400.0, kDepth = 60.0, kRise = 10.0;
  double best_score = 0.0;
  for (double y = lo.y; y <= hi.y; y += kGrid) {
    for (double x = lo.x; x <= hi.x; x += kGrid) {
      if (!is_open(w.biome_at(x, y))) continue;
      const double z0 = w.ground_height(x, y);
      for (int k = 0; k < 8; ++k) {
        const double a = k * 3.14159265358979323846 / 4.0;
        const glm::dvec2 dir(std::cos(a), std::sin(a));
        double run = 0.0;
        bool ok = true;
        for (run = kStep; run <= kMaxRun + kStep; run += kStep) {
          const glm::dvec2 q = glm::dvec2(x, y) + dir * run;
          if (!w.contains_xy(q.x, q.y)) {
            ok = false;
            break;
          }
          const Biome b = w.biome_at(q.x, q.y);
          if (b == Biome::Forest) break;
          if (!is_open(b) || std::abs(w.ground_height(q.x, q.y) - z0) > kRise) {
            ok = false;
            break;
          }
        }
        if (!ok || run > kMaxRun || run <= best_score) continue;
        // The forest must be a real stand, not a few trees.
        bool deep = true;
        for (double e = 0.0; e <= kDepth; e += kStep) {
          const glm::dvec2 q = glm::dvec2(x, y) + dir * (run + e);
          if (!w.contains_xy(q.x, q.y) || w.biome_at(q.x, q.y) != Biome::Forest) {
            deep = false;
            break;
          }
        }
        if (!deep) continue;
        best_score = run;
        const glm::dvec2 e2 = glm::dvec2(x, y) + dir * run;
        best = {true, {x, y, z0}, dir, run, {e2.x, e2.y, w.ground_height(e2.x, e2.y)}};
      }
    }
  }
  return best;
}

}  // namespace

WorldLandmarks find_landmarks(const World& w) {
  WorldLandmarks out;
  out.forest_edge = find_forest_edge(w);
  const Spline3& road = w.road();
  if (road.empty()) return out;
  const double side = 0.5 * w.road_width_m() + w.params().road.shoulder_m + 20.0;
  for (double s = 0.0; s <= road.length(); s += 8.0) {
    const glm::dvec3 p = road.at(s), t = road.tangent(s);
    const glm::dvec2 n = glm::normalize(glm::dvec2(-t.y, t.x));
    const glm::dvec2 l = glm::dvec2(p) + n * side, r = glm::dvec2(p) - n * side;
    if (!w.contains_xy(l.x, l.y) || !w.contains_xy(r.x, r.y)) continue;
    const double dl = w.ground_height(l.x, l.y) - p.z, dr = w.ground_height(r.x, r.y) - p.z;
    const double cut = std::min(dl, dr), emb = std::max(dl, dr);
    if (cut > 0.0 && cut > out.deepest_cutting.relief_m) out.deepest_cutting = {true, s, p, cut};
    if (emb < 0.0 && emb < out.highest_embankment.relief_m) {
      out.highest_embankment = {true, s, p, emb};
    }
  }
  return out;
}

}  // namespace ambisim
