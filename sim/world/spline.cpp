#include "sim/world/spline.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace ambisim {
namespace {

// Centripetal knot spacing: |p1 - p0|^0.5.
double knot_step(const glm::dvec3& a, const glm::dvec3& b) {
  return std::max(std::sqrt(glm::length(b - a)), 1e-9);
}

}  // namespace

Spline3::Spline3(std::vector<glm::dvec3> points, int samples_per_segment) {
  for (const auto& p : points) {
    if (points_.empty() || glm::length(p - points_.back()) > 1e-9) points_.push_back(p);
  }
  if (points_.size() < 2) throw std::invalid_argument("Spline3 needs at least 2 distinct points");
  const int segments = static_cast<int>(points_.size()) - 1;
  // Each segment's knots and mirrored end points, computed once: eval() runs millions of
  // times per run (every vehicle's lane point and tangent, every frame).
  knots_.resize(static_cast<std::size_t>(segments));
  for (int i = 0; i < segments; ++i) {
    const glm::dvec3 p1 = points_[i];
    const glm::dvec3 p2 = points_[i + 1];
    // Mirror the end points so the curve passes through the first and last control points.
    const glm::dvec3 p0 = i > 0 ? points_[i - 1] : 2.0 * p1 - p2;
    const glm::dvec3 p3 = i + 2 <= segments ? points_[i + 2] : 2.0 * p2 - p1;
    Knots& k = knots_[static_cast<std::size_t>(i)];
    k.p0 = p0;
    k.p3 = p3;
    k.t1 = 0.0 + knot_step(p0, p1);
    k.t2 = k.t1 + knot_step(p1, p2);
    k.t3 = k.t2 + knot_step(p2, p3);
  }
  const int n = segments * std::max(samples_per_segment, 1);
  table_t_.resize(static_cast<std::size_t>(n) + 1);
  table_s_.resize(static_cast<std::size_t>(n) + 1);
  table_p_.resize(static_cast<std::size_t>(n) + 1);
  glm::dvec3 prev = eval(0.0);
  table_p_[0] = prev;
  table_t_[0] = 0.0;
  table_s_[0] = 0.0;
  for (int k = 1; k <= n; ++k) {
    const double t = static_cast<double>(k) * segments / n;
    const glm::dvec3 p = eval(t);
    table_t_[k] = t;
    table_s_[k] = table_s_[k - 1] + glm::length(p - prev);
    table_p_[k] = p;
    prev = p;
  }
  build_buckets();
  build_coarse_tree();
}

glm::dvec3 Spline3::eval(double t) const {
  const int i = std::clamp(static_cast<int>(std::floor(t)), 0, static_cast<int>(knots_.size()) - 1);
  const double u = t - i;
  const Knots& k = knots_[static_cast<std::size_t>(i)];
  // Barry-Goldman pyramid for the non-uniform (centripetal) Catmull-Rom, t0 = 0.
  const double t0 = 0.0, t1 = k.t1, t2 = k.t2, t3 = k.t3;
  const glm::dvec3 &p0 = k.p0, &p1 = points_[i], &p2 = points_[i + 1], &p3 = k.p3;
  const double tt = t1 + u * (t2 - t1);
  const glm::dvec3 a1 = ((t1 - tt) * p0 + (tt - t0) * p1) / (t1 - t0);
  const glm::dvec3 a2 = ((t2 - tt) * p1 + (tt - t1) * p2) / (t2 - t1);
  const glm::dvec3 a3 = ((t3 - tt) * p2 + (tt - t2) * p3) / (t3 - t2);
  const glm::dvec3 b1 = ((t2 - tt) * a1 + (tt - t0) * a2) / (t2 - t0);
  const glm::dvec3 b2 = ((t3 - tt) * a2 + (tt - t1) * a3) / (t3 - t1);
  return ((t2 - tt) * b1 + (tt - t1) * b2) / (t2 - t1);
}

std::size_t Spline3::first_sample_after(double s) const {
  // Start at the bucket's first sample, then step to the first sample beyond s, both ways: the
  // answer does not depend on the bucket being right, only the number of steps does (about one,
  // as there are as many buckets as samples).
  if (bucket_first_.empty()) return first_sample_after_reference(s);
  const double b = std::floor(s * inverse_bucket_m_);
  const std::size_t last_bucket = bucket_first_.size() - 1;
  std::size_t k =
      bucket_first_[!(b > 0.0)                              ? 0
                    : b >= static_cast<double>(last_bucket) ? last_bucket
                                                            : static_cast<std::size_t>(b)];
  while (k > 0 && table_s_[k - 1] > s) --k;
  while (k < table_s_.size() && table_s_[k] <= s) ++k;
  return k;
}

std::size_t Spline3::first_sample_after_reference(double s) const {
  return static_cast<std::size_t>(std::upper_bound(table_s_.begin(), table_s_.end(), s) -
                                  table_s_.begin());
}

void Spline3::build_buckets() {
  // Bucket b starts at arc length b / inverse_bucket_m_ and holds the first sample beyond it.
  const std::size_t n = table_s_.size();
  bucket_first_.clear();
  if (!(length() > 0.0)) return;
  inverse_bucket_m_ = static_cast<double>(n) / length();
  bucket_first_.resize(n);
  std::size_t k = 0;
  for (std::size_t b = 0; b < n; ++b) {
    const double start = static_cast<double>(b) / inverse_bucket_m_;
    while (k < n && table_s_[k] <= start) ++k;
    bucket_first_[b] = k;
  }
}

double Spline3::param_at(double s) const {
  s = std::clamp(s, 0.0, length());
  const std::size_t k = first_sample_after(s);
  if (k == table_s_.size()) return table_t_.back();
  if (k == 0) return table_t_.front();
  const double ds = table_s_[k] - table_s_[k - 1];
  const double f = ds > 0.0 ? (s - table_s_[k - 1]) / ds : 0.0;
  return table_t_[k - 1] + f * (table_t_[k] - table_t_[k - 1]);
}

glm::dvec3 Spline3::at(double s) const { return eval(param_at(s)); }

glm::dvec3 Spline3::tangent(double s) const {
  // Central difference over a short arc; one-sided at the ends.
  const double h = std::min(0.25, 0.5 * length());
  const double a = std::clamp(s - h, 0.0, length());
  const double b = std::clamp(s + h, 0.0, length());
  const glm::dvec3 d = at(b) - at(a);
  const double len = glm::length(d);
  return len > 0.0 ? d / len : glm::dvec3(1.0, 0.0, 0.0);
}

// Coarse pass over every kCoarseStride-th table sample, then an exact pass over the polyline
// segments around the best coarse sample. Exact for curves whose bends are gentle at the
// table's scale (roads, camera paths); a hairpin tighter than kCoarseStride samples could
// return a local minimum.
double Spline3::closest_s(const glm::dvec3& p) const {
  if (table_p_.empty()) return 0.0;
  return refine_around(p, nearest_coarse(p));
}

double Spline3::closest_s_reference(const glm::dvec3& p) const {
  if (table_p_.empty()) return 0.0;
  return refine_around(p, nearest_coarse_scan(p));
}

std::size_t Spline3::nearest_coarse_scan(const glm::dvec3& p) const {
  std::size_t best_k = 0;
  double best_c = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < table_p_.size(); k += kCoarseStride) {
    const glm::dvec3& q = table_p_[k];
    const double d2 = glm::dot(p - q, p - q);
    if (d2 < best_c) {
      best_c = d2;
      best_k = k;
    }
  }
  return best_k;
}

std::size_t Spline3::nearest_coarse(const glm::dvec3& p) const {
  // Branch and bound, nearer child first. A node is skipped only when every sample in it is
  // provably farther than the best so far (with a margin far above the rounding of the bound),
  // and ties go to the lower index, so the answer is the scan's, bit for bit.
  std::size_t best_k = 0;
  double best_c = std::numeric_limits<double>::infinity();
  std::int32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const CoarseNode& node = coarse_tree_[static_cast<std::size_t>(stack[--top])];
    const double lower = glm::length(p - node.centre) - node.radius;
    if (lower > 0.0 && lower * lower > best_c * (1.0 + 1e-9)) continue;
    if (node.left < 0) {
      for (std::size_t j = node.first; j < node.last; ++j) {
        const std::size_t k = j * kCoarseStride;
        const glm::dvec3& q = table_p_[k];
        const double d2 = glm::dot(p - q, p - q);
        if (d2 < best_c || (d2 == best_c && k < best_k)) {
          best_c = d2;
          best_k = k;
        }
      }
      continue;
    }
    const CoarseNode& l = coarse_tree_[static_cast<std::size_t>(node.left)];
    const CoarseNode& r = coarse_tree_[static_cast<std::size_t>(node.right)];
    const bool left_nearer =
        glm::length(p - l.centre) - l.radius <= glm::length(p - r.centre) - r.radius;
    stack[top++] = left_nearer ? node.right : node.left;  // popped last
    stack[top++] = left_nearer ? node.left : node.right;
  }
  return best_k;
}

void Spline3::build_coarse_tree() {
  // Leaves of up to 8 coarse samples; a balanced split keeps the depth at log2(m / 8) + 1,
  // far below the search's stack of 64 for any table that fits in memory.
  constexpr std::uint32_t kLeaf = 8;
  const auto m = static_cast<std::uint32_t>((table_p_.size() + kCoarseStride - 1) / kCoarseStride);
  coarse_tree_.clear();
  struct Build {
    Spline3& s;
    std::int32_t operator()(std::uint32_t first, std::uint32_t last) {
      const auto index = static_cast<std::int32_t>(s.coarse_tree_.size());
      s.coarse_tree_.emplace_back();
      glm::dvec3 lo(std::numeric_limits<double>::infinity());
      glm::dvec3 hi(-std::numeric_limits<double>::infinity());
      for (std::uint32_t j = first; j < last; ++j) {
        lo = glm::min(lo, s.table_p_[j * kCoarseStride]);
        hi = glm::max(hi, s.table_p_[j * kCoarseStride]);
      }
      const glm::dvec3 centre = 0.5 * (lo + hi);
      double radius = 0.0;
      for (std::uint32_t j = first; j < last; ++j) {
        radius = std::max(radius, glm::length(s.table_p_[j * kCoarseStride] - centre));
      }
      std::int32_t left = -1, right = -1;
      if (last - first > kLeaf) {
        const std::uint32_t mid = first + (last - first) / 2;
        left = (*this)(first, mid);
        right = (*this)(mid, last);
      }
      CoarseNode& node = s.coarse_tree_[static_cast<std::size_t>(index)];
      node.centre = centre;
      // Inflated so that rounding in the search's bound can never skip a sample on the sphere.
      node.radius = radius * (1.0 + 1e-12) + 1e-9;
      node.first = first;
      node.last = last;
      node.left = left;
      node.right = right;
      return index;
    }
  };
  Build{*this}(0, m);
}

double Spline3::refine_around(const glm::dvec3& p, std::size_t best_k) const {
  const std::size_t n = table_s_.size();
  const std::size_t lo = best_k > kCoarseStride ? best_k - kCoarseStride : 0;
  const std::size_t hi = std::min(n - 1, best_k + kCoarseStride);
  double best_s = 0.0;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (std::size_t k = lo; k < hi; ++k) {
    const glm::dvec3& a = table_p_[k];
    const glm::dvec3& b = table_p_[k + 1];
    const glm::dvec3 ab = b - a;
    const double len2 = glm::dot(ab, ab);
    const double f = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
    const glm::dvec3 q = a + f * ab;
    const double d2 = glm::dot(p - q, p - q);
    if (d2 < best_d2) {
      best_d2 = d2;
      best_s = table_s_[k] + f * (table_s_[k + 1] - table_s_[k]);
    }
  }
  return best_s;
}

}  // namespace ambisim
