#include "sim/render/ray_march.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ambisim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Height tolerance of the inside tests: z at a clip point recomputed from t can land a few
// ulps above the surface it was clipped to; the exact entry comes from column_entry anyway.
constexpr double kZEps = 1e-6;

// A ray in grid-local coordinates (origin-relative xy), so a far-away origin costs no precision.
struct LocalRay {
  glm::dvec3 o, d;
};

LocalRay to_local(const World& w, const glm::dvec3& o, const glm::dvec3& d) {
  const glm::dvec2 l = w.to_local(o.x, o.y);
  return {{l.x, l.y, o.z}, d};
}

// Parameter interval of the ray inside the grid footprint and between the lowest and highest
// column tops.
// `t_xy` is where the ray enters the footprint (0 if it starts inside).
bool clip_to_grid(const World& w, const LocalRay& r, double& t0, double& t1, double& t_xy) {
  t0 = 0.0;
  t1 = kInf;
  const double ext[2] = {w.nx() * w.cell_m(), w.ny() * w.cell_m()};
  for (int a = 0; a < 2; ++a) {
    if (r.d[a] == 0.0) {
      if (r.o[a] < 0.0 || r.o[a] > ext[a]) return false;
      continue;
    }
    double ta = (0.0 - r.o[a]) / r.d[a], tb = (ext[a] - r.o[a]) / r.d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  t_xy = t0;
  if (t0 > t1) return false;
  const double zmax = w.max_surface();
  if (r.d.z > 0.0) {
    t1 = std::min(t1, (zmax - r.o.z) / r.d.z);
  } else if (r.d.z < 0.0) {
    t0 = std::max(t0, (zmax - r.o.z) / r.d.z);
    // Below the lowest column top everything in the footprint is solid: the span ends 1 mm
    // below it (a non-empty span even over flat ground; finite t1 for vertical rays).
    t1 = std::min(t1, (w.min_surface() - 1e-3 - r.o.z) / r.d.z);
  } else if (r.o.z > zmax) {
    return false;
  }
  return t0 <= t1;
}

// Exact entry of the ray into column (ix, iy) = box [x0, x1] x [y0, y1] x (-inf, top]:
// the slab method; the face is the slab whose entry is last. The one definition both
// marchers use, so equal cells give equal faces and distances.
bool column_entry(const World& w, const LocalRay& r, int ix, int iy, RayHit& hit) {
  const double c = w.cell_m();
  const double lo[2] = {ix * c, iy * c};
  const double top = w.column_top(ix, iy);
  double t_in = -kInf, t_out = kInf;
  ColumnFace face = ColumnFace::Inside;
  for (int a = 0; a < 2; ++a) {
    if (r.d[a] == 0.0) {
      if (r.o[a] < lo[a] || r.o[a] > lo[a] + c) return false;
      continue;
    }
    const double ta = (lo[a] - r.o[a]) / r.d[a], tb = (lo[a] + c - r.o[a]) / r.d[a];
    const bool pos = r.d[a] > 0.0;
    const double enter = pos ? ta : tb, leave = pos ? tb : ta;
    if (enter > t_in) {
      t_in = enter;
      // Entering while moving +x means crossing the column's -x wall.
      face = a == 0 ? (pos ? ColumnFace::WallNegX : ColumnFace::WallPosX)
                    : (pos ? ColumnFace::WallNegY : ColumnFace::WallPosY);
    }
    t_out = std::min(t_out, leave);
  }
  if (r.d.z < 0.0) {
    const double tz = (top - r.o.z) / r.d.z;
    if (tz > t_in) {
      t_in = tz;
      face = ColumnFace::Top;
    }
  } else if (r.d.z > 0.0) {
    t_out = std::min(t_out, (top - r.o.z) / r.d.z);
  } else if (r.o.z > top) {
    return false;
  }
  if (t_in > t_out || t_out < 0.0) return false;
  hit.kind = HitKind::Column;
  hit.ix = ix;
  hit.iy = iy;
  if (t_in < -1e-9) {  // the ray starts inside this column
    hit.face = ColumnFace::Inside;
    hit.t = 0.0;
  } else {
    hit.face = face;
    hit.t = std::max(t_in, 0.0);
  }
  return true;
}

// What a ray meets once it has left (or never entered) the grid: far ground or sky.
RayHit outside_hit(const World& w, const LocalRay& r) {
  RayHit h;
  if (r.d.z < 0.0) {
    h.kind = HitKind::FarGround;
    h.t = std::max(0.0, (w.far_ground_height() - r.o.z) / r.d.z);
  } else {
    h.kind = HitKind::Sky;
    h.t = kInf;
  }
  return h;
}

// The far-ground plane lies below every column, so a ray can reach it first only outside
// the grid, i.e. before entering the footprint at t_xy.
bool far_ground_first(const World& w, const LocalRay& r, double t_xy) {
  return r.d.z < 0.0 && (w.far_ground_height() - r.o.z) / r.d.z < t_xy;
}

struct Traversal {
  const World& w;
  const HeightPyramid& pyr;
  const LocalRay& r;
  RayHit hit;

  // Node (level, ix, iy) with the ray's xy span [ta, tb] inside it.
  bool visit(int level, int ix, int iy, double ta, double tb) {
    const double za = r.o.z + r.d.z * ta, zb = r.o.z + r.d.z * tb;
    // z is linear in t, so its minimum over the span is at an end.
    if (std::min(za, zb) > pyr.max_at(level, ix, iy) + kZEps) return false;
    if (level == 0) return column_entry(w, r, ix, iy, hit);
    const double child = w.cell_m() * static_cast<double>(1 << (level - 1));
    const double xm = (2 * ix + 1) * child, ym = (2 * iy + 1) * child;
    double split[2];
    int n = 0;
    if (r.d.x != 0.0) {
      const double t = (xm - r.o.x) / r.d.x;
      if (t > ta && t < tb) split[n++] = t;
    }
    if (r.d.y != 0.0) {
      const double t = (ym - r.o.y) / r.d.y;
      if (t > ta && t < tb) split[n++] = t;
    }
    if (n == 2 && split[0] > split[1]) std::swap(split[0], split[1]);
    double s0 = ta;
    for (int k = 0; k <= n; ++k) {
      const double s1 = k < n ? split[k] : tb;
      // The piece's midpoint decides the child robustly (ends lie on the split lines).
      const double tm = 0.5 * (s0 + s1);
      const int cx = r.o.x + r.d.x * tm >= xm ? 1 : 0;
      const int cy = r.o.y + r.d.y * tm >= ym ? 1 : 0;
      if (visit(level - 1, 2 * ix + cx, 2 * iy + cy, s0, s1)) return true;
      s0 = s1;
    }
    return false;
  }
};

// --- Fast traversal -------------------------------------------------------------------------
//
// The recursive traversal above is the definition; the loop below finds the same first hit
// at a fraction of the cost (the same cell and face, the same exact entry distance, except
// for rays that graze a cell corner or edge within rounding error). It walks the max-mip
// nodes front to back (descend when a node may hold the hit, skip it and ascend when it
// cannot) with reciprocal arithmetic in cell units and an extra height margin, so culling is
// conservative; a leaf that cannot be culled is decided by the exact column_entry, which
// tests the whole column box. The walk visits the cells the ray crosses in order, so the
// first leaf whose column the ray enters holds the first hit.
//
// Rays the loop is not made for (nearly vertical or nearly axis-parallel ones, whose culling
// margins it does not cover, and rays passing a cell corner within rounding error) are left
// to the recursion. A ray starting on a cell wall starts in the cell ahead of it.

constexpr double kTieM = 1e-7;        // distance to a wall that counts as on the wall
constexpr double kCullMargin = 1e-5;  // extra height margin of the approximate node culling

// Leaf cell of coordinate x on one axis (n cells of size c) where a ray moving with
// component d starts: on (or within rounding error of) an interior wall, the cell ahead.
inline int start_cell(double x, double d, double c, double inv_c, int n) {
  const double f = std::clamp(x * inv_c, 0.0, static_cast<double>(n));
  const int i = std::min(static_cast<int>(f), n - 1);
  const int m = static_cast<int>(f + 0.5);  // nearest wall
  if (m > 0 && m < n && std::abs(x - m * c) < kTieM && d != 0.0) return d > 0.0 ? m : m - 1;
  return i;
}

enum class FastResult { Hit, Miss, Undecided };

FastResult march_fast(const World& w, const LocalRay& r, double t0, double t1, RayHit& hit) {
  const double dx = r.d.x, dy = r.d.y, dz = r.d.z;
  const double adx = std::abs(dx), ady = std::abs(dy);
  // Nearly vertical or nearly axis-parallel rays: the culling margins assume |d.x|, |d.y| are
  // either 0 or not tiny. (Vertical rays cross no wall; the recursion is cheap for them.)
  if (adx < 1e-4 && ady < 1e-4) return FastResult::Undecided;
  if ((dx != 0.0 && adx < 1e-4) || (dy != 0.0 && ady < 1e-4)) return FastResult::Undecided;
  const HeightPyramid& pyr = w.pyramid();
  const double c = w.cell_m();
  const int nx = w.nx(), ny = w.ny(), top = pyr.levels() - 1, side = pyr.size(0);
  // Node-wall crossings in cell units: t = (wall - o / c) * (c / d).
  const double inv_c = 1.0 / c, oxc = r.o.x * inv_c, oyc = r.o.y * inv_c;
  const double idx = dx != 0.0 ? c / dx : 0.0, idy = dy != 0.0 ? c / dy : 0.0;
  const double dxc = dx * inv_c, dyc = dy * inv_c;
  const int sx = dx > 0.0 ? 1 : 0, sy = dy > 0.0 ? 1 : 0;
  // Passing a cell corner within rounding error (an x and a y wall crossed at nearly the same
  // t) leaves the order of the two cells ahead, and so the cell hit first when the ray grazes
  // an edge, to rounding: such rays are left to the recursion. Separations are measured as
  // |delta t| * sep, and a wall offset in cell units as |delta| * kx (resp. ky).
  const double sep = std::min(dx != 0.0 ? adx : 1.0, dy != 0.0 ? ady : 1.0);
  const double kx = sep * std::abs(idx), ky = sep * std::abs(idy);

  int ix = start_cell(r.o.x + dx * t0, dx, c, inv_c, nx);
  int iy = start_cell(r.o.y + dy * t0, dy, c, inv_c, ny);
  // Start at the largest node around the start that lies wholly below the ray's start
  // height (low in cuttings and forests, high in the air); the walk ascends from there.
  int level = 0;
  {
    const double z0 = r.o.z + dz * t0;
    while (level < top && pyr.max_at(level + 1, ix >> (level + 1), iy >> (level + 1)) < z0) {
      ++level;
    }
  }
  const float* lv = pyr.level_data(level);
  const double margin = kZEps + kCullMargin;
  double t = t0;
  for (;;) {
    const int mx = ix >> level, my = iy >> level;
    // The walls crossed when leaving the node through x / y, and when.
    const int bx = (mx + sx) << level, by = (my + sy) << level;
    const double tx = dx != 0.0 ? (bx - oxc) * idx : kInf;
    const double ty = dy != 0.0 ? (by - oyc) * idy : kInf;
    const double t_wall = std::min(tx, ty);
    const double z_low = dz < 0.0 ? r.o.z + dz * std::min(t_wall, t1) : r.o.z + dz * t;
    const double h_max = lv[static_cast<std::size_t>(my) * static_cast<std::size_t>(side >> level) +
                            static_cast<std::size_t>(mx)];
    if (!(z_low > h_max + margin)) {
      if (level > 0) {
        --level;
        lv = pyr.level_data(level);
        continue;
      }
      // A leaf that may hold the hit: the exact entry into its column.
      if (column_entry(w, r, ix, iy, hit)) return FastResult::Hit;
    }
    // Leave the node.
    if (t_wall >= t1) return FastResult::Miss;
    if (std::abs(tx - ty) * sep < kTieM) return FastResult::Undecided;
    int b;
    if (tx < ty) {
      b = bx;
      ix = bx - 1 + sx;
      if (ix < 0 || ix >= nx) return FastResult::Miss;
      if (level > 0 && dy != 0.0) {
        const int lo = my << level, hi = std::min(((my + 1) << level) - 1, ny - 1);
        const double f = std::max(oyc + dyc * tx, 0.0);
        if (std::abs(f - static_cast<int>(f + 0.5)) * ky < kTieM) return FastResult::Undecided;
        iy = std::clamp(static_cast<int>(f), lo, hi);
      }
      t = tx;
    } else {
      b = by;
      iy = by - 1 + sy;
      if (iy < 0 || iy >= ny) return FastResult::Miss;
      if (level > 0 && dx != 0.0) {
        const int lo = mx << level, hi = std::min(((mx + 1) << level) - 1, nx - 1);
        const double f = std::max(oxc + dxc * ty, 0.0);
        if (std::abs(f - static_cast<int>(f + 0.5)) * kx < kTieM) return FastResult::Undecided;
        ix = std::clamp(static_cast<int>(f), lo, hi);
      }
      t = ty;
    }
    // Entering a new parent (grandparent) node: cull at its size again.
    const int before = level;
    for (int a = 0; a < 1 && level < top && (b & ((2 << level) - 1)) == 0; ++a) ++level;
    if (level != before) lv = pyr.level_data(level);
  }
}

}  // namespace

RayHit march_accelerated(const World& w, const glm::dvec3& o, const glm::dvec3& d) {
  const LocalRay r = to_local(w, o, d);
  double t0, t1, t_xy;
  if (!clip_to_grid(w, r, t0, t1, t_xy) || far_ground_first(w, r, t_xy)) {
    return outside_hit(w, r);
  }
  RayHit hit;
  switch (march_fast(w, r, t0, t1, hit)) {
    case FastResult::Hit:
      return hit;
    case FastResult::Miss:
      return outside_hit(w, r);
    case FastResult::Undecided:
      break;
  }
  Traversal tr{w, w.pyramid(), r, {}};
  if (tr.visit(w.pyramid().levels() - 1, 0, 0, t0, t1)) return tr.hit;
  return outside_hit(w, r);
}

RayHit march_naive(const World& w, const glm::dvec3& o, const glm::dvec3& d) {
  const LocalRay r = to_local(w, o, d);
  double t0, t1, t_xy;
  if (!clip_to_grid(w, r, t0, t1, t_xy) || far_ground_first(w, r, t_xy)) {
    return outside_hit(w, r);
  }
  const double c = w.cell_m(), dt = kNaiveStepCells * c;
  auto cell_at = [&](double t, int& ix, int& iy) {
    const glm::dvec3 p = r.o + r.d * t;
    ix = std::clamp(static_cast<int>(std::floor(p.x / c)), 0, w.nx() - 1);
    iy = std::clamp(static_cast<int>(std::floor(p.y / c)), 0, w.ny() - 1);
  };
  int px, py;
  cell_at(t0, px, py);
  double t_prev = t0;
  for (long k = 0;; ++k) {
    const double t = std::min(t0 + static_cast<double>(k) * dt, t1);
    int ix, iy;
    cell_at(t, ix, iy);
    // A step shorter than a cell crosses at most one x and one y boundary, so the cells of
    // the segment [t_prev, t] are among these four; test them all so that corners clipped
    // between two samples are not missed, and keep the earliest entry.
    const int cx[4] = {px, ix, px, ix}, cy[4] = {py, iy, iy, py};
    const double zmin = std::min(r.o.z + r.d.z * t_prev, r.o.z + r.d.z * t);
    RayHit best;
    best.t = kInf;
    for (int q = 0; q < 4; ++q) {
      bool dup = false;
      for (int e = 0; e < q; ++e) dup |= cx[e] == cx[q] && cy[e] == cy[q];
      if (dup || zmin > w.column_top(cx[q], cy[q]) + kZEps) continue;
      RayHit h;
      if (column_entry(w, r, cx[q], cy[q], h) && h.t <= t + kZEps && h.t < best.t) best = h;
    }
    if (best.kind == HitKind::Column) return best;
    if (t >= t1) break;
    t_prev = t;
    px = ix;
    py = iy;
  }
  return outside_hit(w, r);
}

RayHit march(const World& w, const glm::dvec3& o, const glm::dvec3& d, Marcher m) {
  return m == Marcher::accelerated ? march_accelerated(w, o, d) : march_naive(w, o, d);
}

Rgb hit_radiance(const Illumination& il, const glm::dvec3& o, const glm::dvec3& d,
                 const RayHit& h) {
  switch (h.kind) {
    case HitKind::Sky:
      return il.sky(o, d);
    case HitKind::FarGround:
      return il.far_ground(o, d, h.t);
    case HitKind::Column:
      break;
  }
  return il.column(h.ix, h.iy, h.face, o, d, h.t);
}

Rgb hit_radiance(const World& w, const glm::dvec3& o, const glm::dvec3& d, const RayHit& h) {
  return hit_radiance(Illumination(w), o, d, h);
}

}  // namespace ambisim
