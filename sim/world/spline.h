#pragma once
// A smooth curve through control points, parameterised by arc length: used for the road's
// centre line and for keyframed camera paths. Centripetal Catmull-Rom (alpha = 0.5): it never
// forms cusps or self-intersections within a segment, unlike the uniform variant.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace ambisim {

class Spline3 {
 public:
  Spline3() = default;
  // At least 2 points; consecutive duplicates are dropped. `samples_per_segment` sets the
  // density of the arc-length table (the position error of at() is far below it).
  explicit Spline3(std::vector<glm::dvec3> points, int samples_per_segment = 64);

  bool empty() const { return points_.size() < 2; }
  double length() const { return table_s_.empty() ? 0.0 : table_s_.back(); }
  const std::vector<glm::dvec3>& control_points() const { return points_; }

  // Position and unit tangent at arc length s (clamped to [0, length]).
  glm::dvec3 at(double s) const;
  glm::dvec3 tangent(double s) const;
  // Arc length of the point on the curve closest to p (piecewise-linear search, then refined).
  // The coarse search walks a tree of bounding spheres over the coarse samples: O(log n) where
  // a scan of the whole road was O(n), with the same answer to the bit.
  double closest_s(const glm::dvec3& p) const;
  // The same search with the coarse samples scanned one by one: the reference closest_s() is
  // tested against (and the naive path of its benchmark).
  double closest_s_reference(const glm::dvec3& p) const;

  // The index of the first arc-length sample beyond s (std::upper_bound over the samples), for
  // s in [0, length]: found from a bucket per sample's worth of arc length, since every
  // vehicle's lane point asks for it about 9 times per frame. The reference is the binary
  // search, which the test compares it with.
  std::size_t first_sample_after(double s) const;
  std::size_t first_sample_after_reference(double s) const;
  const std::vector<double>& sample_arc_lengths() const { return table_s_; }

 private:
  // Curve parameter t in [0, segments] at arc length s.
  double param_at(double s) const;
  glm::dvec3 eval(double t) const;
  // Every kCoarseStride-th table sample is a coarse sample; the best one, by either search,
  // is the first of the samples nearest p (strict <, as a scan in table order finds it).
  static constexpr std::size_t kCoarseStride = 16;
  std::size_t nearest_coarse(const glm::dvec3& p) const;
  std::size_t nearest_coarse_scan(const glm::dvec3& p) const;
  // The exact pass over the polyline segments within kCoarseStride samples of best_k.
  double refine_around(const glm::dvec3& p, std::size_t best_k) const;
  void build_coarse_tree();
  void build_buckets();

  std::vector<glm::dvec3> points_;
  // Per segment i (points_[i] to points_[i + 1]): the neighbours p0 and p3 (mirrored at the
  // ends) and the centripetal knots t1 < t2 < t3 (t0 = 0).
  struct Knots {
    glm::dvec3 p0, p3;
    double t1, t2, t3;
  };
  std::vector<Knots> knots_;
  std::vector<double> table_t_;  // parameter samples
  std::vector<double> table_s_;  // cumulative arc length at each sample
  // The curve at each sample: closest_s() reads it instead of evaluating the curve again (a
  // planner with route prediction asks several times per frame; 24 B per sample).
  std::vector<glm::dvec3> table_p_;
  // A node holds the coarse samples [first, last) (numbered j: table sample j x kCoarseStride)
  // inside the sphere (centre, radius); an inner node's children split the range in two.
  struct CoarseNode {
    glm::dvec3 centre{0.0};
    double radius = 0.0;
    std::uint32_t first = 0, last = 0;
    std::int32_t left = -1, right = -1;  // -1: a leaf
  };
  std::vector<CoarseNode> coarse_tree_;  // root first
  // bucket_first_[b]: first_sample_after(b / inverse_bucket_m_); one bucket per sample.
  std::vector<std::size_t> bucket_first_;
  double inverse_bucket_m_ = 0.0;
};

}  // namespace ambisim
