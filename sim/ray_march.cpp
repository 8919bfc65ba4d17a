#include "sim/ray_march.h"

#include <algorithm>
#include <bit>
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
// The recursive traversal above is the definition; the loop below reproduces its result bit
// for bit at a fraction of the cost. What the recursion returns is fixed by its sequence of
// leaf pieces: the cells the ray crosses, in order, each with the span [ta, tb] between the
// crossings of its walls (computed as (plane - o) / d with the plane coordinates the recursion
// uses), and the first leaf that passes the height test and column_entry. Node culling above
// the leaves only skips leaves that would fail the test anyway (z is monotone in t, a node's
// maximum bounds its cells), so any conservative culling gives the same answer.
//
// The loop walks the max-mip nodes front to back (descend when a node may hold the hit, skip
// it and ascend when it cannot) with cheap reciprocal arithmetic and an extra height margin,
// and recomputes the exact leaf span, test and entry only at leaves it cannot cull. The
// recursion assigns each piece to a child by the piece's midpoint, which matches the
// geometric cell unless the ray passes within rounding error of a cell corner (an x and a y
// crossing nearly simultaneous) or of a wall at the span's ends; whenever the ray comes
// within kTieM metres of such a configuration the fast loop gives up and the recursion
// decides.

constexpr double kTieM = 1e-7;        // separation below which a configuration counts as a tie
constexpr double kCullMargin = 1e-5;  // extra height margin of the approximate node culling

// Coordinate of cell-boundary plane m (0 < m), computed exactly as the recursion computes the
// split plane of a node: (2 i + 1) * (cell * 2^(level - 1)) with m = (2 i + 1) 2^(level - 1).
double plane_coord(double c, int m) {
  const int k = std::countr_zero(static_cast<unsigned>(m));
  return static_cast<double>(m >> k) * (c * static_cast<double>(1 << k));
}

// Leaf cell of coordinate x on one axis (n cells of size c), or false when x lies so close to
// an interior wall that the recursion's choice of side is not certain (k converts the
// distance into the separation measure).
bool axis_cell(double x, double c, double inv_c, int n, double k, int& i) {
  // Truncation instead of floor/round (no libm calls on SSE2; negative x clamps to cell 0) and
  // an approximate 1 / c: near a wall, where either could be off by one, the tie test fails.
  const double f = std::clamp(x * inv_c, -1.0, n + 1.0);
  i = std::clamp(static_cast<int>(f), 0, n - 1);
  const int m = static_cast<int>(f + 0.5);  // nearest wall (f >= -0.5; walls below 1 are edges)
  return !(m > 0 && m < n && std::abs(x - m * c) * k < kTieM);
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
  // A piece of length dt keeps its midpoint sep * dt / 2 away from the walls it lies between.
  const double sep = std::min(dx != 0.0 ? adx : 1.0, dy != 0.0 ? ady : 1.0);
  const double kx = dx != 0.0 ? sep / adx : 1.0, ky = dy != 0.0 ? sep / ady : 1.0;
  // Approximate node-wall crossings in cell units: t = (wall - o / c) * (c / d).
  const double inv_c = 1.0 / c, oxc = r.o.x * inv_c, oyc = r.o.y * inv_c;
  const double idx = dx != 0.0 ? c / dx : 0.0, idy = dy != 0.0 ? c / dy : 0.0;

  int ix, iy;
  if (!axis_cell(r.o.x + dx * t0, c, inv_c, nx, kx, ix) ||
      !axis_cell(r.o.y + dy * t0, c, inv_c, ny, ky, iy)) {
    return FastResult::Undecided;
  }
  // Start at the largest node around the start that lies wholly below the ray's start
  // height (low in cuttings and forests, high in the air); the walk ascends from there.
  int level = 0;
  {
    const double z0 = r.o.z + dz * t0;
    while (level < top && pyr.max_at(level + 1, ix >> (level + 1), iy >> (level + 1)) < z0) {
      ++level;
    }
  }
  double t = t0;
  for (;;) {
    const int mx = ix >> level, my = iy >> level;
    double tx = kInf, ty = kInf;
    int bx = 0, by = 0;  // the walls crossed when leaving the node through x / y
    if (dx > 0.0) {
      bx = (mx + 1) << level;
      tx = (bx - oxc) * idx;
    } else if (dx < 0.0) {
      bx = mx << level;
      tx = (bx - oxc) * idx;
    }
    if (dy > 0.0) {
      by = (my + 1) << level;
      ty = (by - oyc) * idy;
    } else if (dy < 0.0) {
      by = my << level;
      ty = (by - oyc) * idy;
    }
    const double t_exit = std::min(std::min(tx, ty), t1);
    const double z_low = dz < 0.0 ? r.o.z + dz * t_exit : r.o.z + dz * t;
    const double h_max = pyr.level_data(
        level)[static_cast<std::size_t>(my) * static_cast<std::size_t>(side >> level) +
               static_cast<std::size_t>(mx)];
    if (!(z_low > h_max + kZEps + kCullMargin)) {
      if (level > 0) {
        --level;
        continue;
      }
      // A leaf that may hold the hit: the recursion's exact span and test.
      double ta = t0, tb = t1;
      if (dx != 0.0) {
        const int m_in = dx > 0.0 ? ix : ix + 1, m_out = dx > 0.0 ? ix + 1 : ix;
        if (m_in > 0 && m_in < nx) ta = std::max(ta, (plane_coord(c, m_in) - r.o.x) / dx);
        if (m_out > 0 && m_out < nx) tb = std::min(tb, (plane_coord(c, m_out) - r.o.x) / dx);
      }
      if (dy != 0.0) {
        const int m_in = dy > 0.0 ? iy : iy + 1, m_out = dy > 0.0 ? iy + 1 : iy;
        if (m_in > 0 && m_in < ny) ta = std::max(ta, (plane_coord(c, m_in) - r.o.y) / dy);
        if (m_out > 0 && m_out < ny) tb = std::min(tb, (plane_coord(c, m_out) - r.o.y) / dy);
      }
      if ((tb - ta) * sep < kTieM) return FastResult::Undecided;
      const double za = r.o.z + dz * ta, zb = r.o.z + dz * tb;
      if (!(std::min(za, zb) > pyr.max_at(0, ix, iy) + kZEps) && column_entry(w, r, ix, iy, hit)) {
        return FastResult::Hit;
      }
    }
    // Leave the node.
    const double t_wall = std::min(tx, ty);
    const bool wall_x = tx < ty;
    const int b = wall_x ? bx : by, n_axis = wall_x ? nx : ny;
    if (b > 0 && b < n_axis && std::abs(t1 - t_wall) * sep < kTieM) return FastResult::Undecided;
    if (t_wall >= t1) return FastResult::Miss;
    if (std::abs(tx - ty) * sep < kTieM) return FastResult::Undecided;
    if (wall_x) {
      ix = dx > 0.0 ? bx : bx - 1;
      if (ix < 0 || ix >= nx) return FastResult::Miss;
      if (dy != 0.0) {
        const int lo = my << level, hi = std::min(((my + 1) << level) - 1, ny - 1);
        int cy;
        if (!axis_cell(r.o.y + dy * tx, c, inv_c, ny, ky, cy)) return FastResult::Undecided;
        iy = std::clamp(cy, lo, hi);
      }
      t = tx;
    } else {
      iy = dy > 0.0 ? by : by - 1;
      if (iy < 0 || iy >= ny) return FastResult::Miss;
      if (dx != 0.0) {
        const int lo = mx << level, hi = std::min(((mx + 1) << level) - 1, nx - 1);
        int cx;
        if (!axis_cell(r.o.x + dx * ty, c, inv_c, nx, kx, cx)) return FastResult::Undecided;
        ix = std::clamp(cx, lo, hi);
      }
      t = ty;
    }
    // Entering a new parent (grandparent) node: cull at its size again.
    for (int a = 0; a < 2 && level < top && (b & ((2 << level) - 1)) == 0; ++a) ++level;
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

Rgb hit_radiance(const World& w, const glm::dvec3& o, const glm::dvec3& d, const RayHit& h) {
  const Lighting& light = w.lighting();
  switch (h.kind) {
    case HitKind::Sky:
      return light.sky_ray(d);
    case HitKind::FarGround:
      return light.apply_fog(w.far_ground_radiance(), h.t);
    case HitKind::Column:
      break;
  }
  const Rgb l = (h.face == ColumnFace::Top || h.face == ColumnFace::Inside)
                    ? w.top_radiance(h.ix, h.iy)
                    : w.wall_radiance(h.ix, h.iy, h.face, o.z + d.z * h.t);
  return light.apply_fog(l, h.t);
}

}  // namespace ambisim
