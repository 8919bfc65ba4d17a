#include "sim/world/landmarks.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <glm/geometric.hpp>

namespace ambisim {
namespace {

bool is_open(Biome b) { return b == Biome::Grass || b == Biome::Field || b == Biome::Sand; }

// Directions at multiples of 45 degrees, exact on the axes (cos(pi/2) is 6e-17, not 0: a
// landmark frame built from it would move offsets by rounding).
glm::dvec2 compass(int k) {
  constexpr double kDiag = 0.70710678118654752440;
  static constexpr double kX[8] = {1.0, kDiag, 0.0, -kDiag, -1.0, -kDiag, 0.0, kDiag};
  static constexpr double kY[8] = {0.0, kDiag, 1.0, kDiag, 0.0, -kDiag, -1.0, -kDiag};
  return {kX[k & 7], kY[k & 7]};
}

ForestEdgeApproach find_forest_edge(const World& w) {
  ForestEdgeApproach best;
  const glm::dvec2 lo = w.min_xy() + glm::dvec2(200.0), hi = w.max_xy() - glm::dvec2(200.0);
  constexpr double kGrid = 32.0, kStep = 4.0, kMaxRun = 400.0, kDepth = 60.0, kRise = 10.0;
  // Room for a flight over the forest (500 m; a fifth of a small world's side).
  const glm::dvec2 extent = w.max_xy() - w.min_xy();
  const double kEdgeMargin = std::min(500.0, 0.2 * std::min(extent.x, extent.y));
  double best_score = 0.0;
  for (double y = lo.y; y <= hi.y; y += kGrid) {
    for (double x = lo.x; x <= hi.x; x += kGrid) {
      if (!is_open(w.biome_at(x, y))) continue;
      const double z0 = w.ground_height(x, y);
      for (int k = 0; k < 8; ++k) {
        const double a = k * 3.14159265358979323846 / 4.0;
        // The scan steps along cos/sin (the start and edge it finds stay as they were); the
        // direction it reports is the exact compass direction.
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
        const glm::dvec2 e2 = glm::dvec2(x, y) + dir * run;
        // Room for a flight over the forest: the edge stands well inside the world.
        if (e2.x - w.min_xy().x < kEdgeMargin || w.max_xy().x - e2.x < kEdgeMargin ||
            e2.y - w.min_xy().y < kEdgeMargin || w.max_xy().y - e2.y < kEdgeMargin) {
          continue;
        }
        best_score = run;
        best = {true, {x, y, z0}, compass(k), run, {e2.x, e2.y, w.ground_height(e2.x, e2.y)}};
      }
    }
  }
  return best;
}

OutcropLandmark find_outcrop(const World& w) {
  OutcropLandmark best;
  const glm::dvec2 lo = w.min_xy() + glm::dvec2(300.0), hi = w.max_xy() - glm::dvec2(300.0);
  constexpr double kGrid = 16.0, kRadius = 80.0, kMinProminence = 15.0;
  constexpr int kRing = 16;
  for (double y = lo.y; y <= hi.y; y += kGrid) {
    for (double x = lo.x; x <= hi.x; x += kGrid) {
      if (w.biome_at(x, y) != Biome::Rock) continue;
      const double z = w.ground_height(x, y);
      double around = 0.0;
      for (int k = 0; k < kRing; ++k) {
        const double a = 2.0 * 3.14159265358979323846 * k / kRing;
        around += w.ground_height(x + kRadius * std::cos(a), y + kRadius * std::sin(a));
      }
      const double prominence = z - around / kRing;
      if (prominence >= kMinProminence && prominence > best.prominence_m) {
        best = {true, {x, y, z}, prominence};
      }
    }
  }
  return best;
}

CliffLandmark find_cliff(const World& w) {
  CliffLandmark best;
  const glm::dvec2 lo = w.min_xy() + glm::dvec2(300.0), hi = w.max_xy() - glm::dvec2(300.0);
  constexpr double kGrid = 8.0, kReach = 16.0, kMinDrop = 20.0;
  for (double y = lo.y; y <= hi.y; y += kGrid) {
    for (double x = lo.x; x <= hi.x; x += kGrid) {
      const Biome b = w.biome_at(x, y);
      if (!is_open(b) && b != Biome::Rock) continue;
      const double z = w.ground_height(x, y);
      for (int k = 0; k < 8; ++k) {
        const glm::dvec2 d = compass(k);
        const glm::dvec2 q = glm::dvec2(x, y) + d * kReach;
        const Biome bq = w.biome_at(q.x, q.y);
        if (bq == Biome::Asphalt || bq == Biome::Water) continue;
        const double drop = z - w.ground_height(q.x, q.y);
        if (drop >= kMinDrop && drop > best.drop_m) best = {true, {x, y, z}, d, drop};
      }
    }
  }
  return best;
}

}  // namespace

glm::dvec3 LandmarkFrame::point(const glm::dvec3& offset) const {
  const glm::dvec2 left(-along.y, along.x);
  return {origin.x + offset.x * along.x + offset.y * left.x,
          origin.y + offset.x * along.y + offset.y * left.y, origin.z + offset.z};
}

const std::vector<std::string>& landmark_names() {
  static const std::vector<std::string> names = {
      "forest_edge", "road.deepest_cutting", "road.highest_embankment", "rock_outcrop", "cliff"};
  return names;
}

bool is_landmark_name(std::string_view name) {
  const auto& n = landmark_names();
  return std::find(n.begin(), n.end(), name) != n.end();
}

std::optional<LandmarkFrame> landmark_frame(const WorldLandmarks& l, std::string_view name) {
  const auto road_frame = [](const RoadLandmark& r, const glm::dvec2& tangent) {
    return std::optional<LandmarkFrame>(LandmarkFrame{r.point, tangent});
  };
  if (name == "forest_edge") {
    if (!l.forest_edge.found) return std::nullopt;
    return LandmarkFrame{l.forest_edge.edge, l.forest_edge.direction};
  }
  if (name == "road.deepest_cutting") {
    if (!l.deepest_cutting.found) return std::nullopt;
    return road_frame(l.deepest_cutting, l.deepest_cutting_tangent);
  }
  if (name == "road.highest_embankment") {
    if (!l.highest_embankment.found) return std::nullopt;
    return road_frame(l.highest_embankment, l.highest_embankment_tangent);
  }
  if (name == "rock_outcrop") {
    if (!l.rock_outcrop.found) return std::nullopt;
    return LandmarkFrame{l.rock_outcrop.top, {1.0, 0.0}};
  }
  if (name == "cliff") {
    if (!l.cliff.found) return std::nullopt;
    return LandmarkFrame{l.cliff.top, l.cliff.direction};
  }
  return std::nullopt;
}

WorldLandmarks find_landmarks(const World& w) {
  WorldLandmarks out;
  out.forest_edge = find_forest_edge(w);
  out.rock_outcrop = find_outcrop(w);
  out.cliff = find_cliff(w);
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
    const glm::dvec2 along = glm::normalize(glm::dvec2(t));
    if (cut > 0.0 && cut > out.deepest_cutting.relief_m) {
      out.deepest_cutting = {true, s, p, cut};
      out.deepest_cutting_tangent = along;
    }
    if (emb < 0.0 && emb < out.highest_embankment.relief_m) {
      out.highest_embankment = {true, s, p, emb};
      out.highest_embankment_tangent = along;
    }
  }
  return out;
}

}  // namespace ambisim
