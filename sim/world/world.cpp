#include "sim/world/world.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <numbers>

#include <glm/geometric.hpp>

#include "sim/base/hash.h"
#include "sim/world/landmarks.h"
#include "sim/world/lighting_model.h"
#include "sim/world/shadow_heights.h"
#include "sim/world/terrain_noise.h"

namespace ambisim {
namespace {

double smoothstep(double a, double b, double x) {
  const double t = std::clamp((x - a) / (b - a), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// Independent sub-seeds per generated layer.
std::uint64_t layer_seed(std::uint64_t seed, std::uint64_t layer) {
  return hash_combine(splitmix64(seed), layer);
}

int octaves_for(double wavelength_m, double cell_m) {
  // Stop once the finest octave is about 4 cells long: shorter ones alias on the grid.
  const int o = static_cast<int>(std::floor(std::log2(wavelength_m / (4.0 * cell_m)))) + 1;
  return std::clamp(o, 1, 8);
}

// Raw terrain heights (before road grading and lakes) of one row of cells at local y.
void raw_height_row(const WorldParams& p, const std::vector<double>& xs, double y, int oct_base,
                    int oct_ridge, std::vector<double>& base, std::vector<double>& ridge,
                    std::vector<double>& cliff, float* out) {
  const TerrainParams& t = p.terrain;
  const int n = static_cast<int>(xs.size());
  fbm_noise_row(layer_seed(p.seed, 1), xs.data(), n, y, t.wavelength_m, oct_base, t.roughness,
                base.data());
  ridged_noise_row(layer_seed(p.seed, 2), xs.data(), n, y, 0.55 * t.wavelength_m, oct_ridge, 0.5,
                   ridge.data());
  // Escarpments: a narrow band of a low-frequency field lifts one side by cliff_height_m.
  fbm_noise_row(layer_seed(p.seed, 3), xs.data(), n, y, 0.8 * t.wavelength_m, 3, 0.45,
                cliff.data());
  for (int i = 0; i < n; ++i) {
    // fBm of value noise concentrates around 0.5: stretch it to use the amplitude.
    const double b = std::clamp(0.5 + (base[i] - 0.5) * 2.6, 0.0, 1.2);
    // Ridges grow on high ground only, so valleys stay rolling and crests turn sharp.
    const double r = ridge[i];
    const double h = t.amplitude_m * ((1.0 - t.ridge_weight) * b +
                                      t.ridge_weight * r * r * 1.6 * smoothstep(0.35, 0.9, b));
    out[i] = static_cast<float>(h + t.cliff_height_m * smoothstep(0.495, 0.505, cliff[i]));
  }
}

struct RoadStamp {
  std::vector<float> dist;    // horizontal distance to the centre line (inf if far)
  std::vector<float> road_z;  // road surface height at the nearest centre-line point
};

// Road centre line in local coordinates: winding west to east, graded by smoothing the
// terrain profile (cuttings where the hills rise above it, embankments where they fall).
std::vector<glm::dvec3> road_polyline(const WorldParams& p, const std::vector<float>& h, int nx,
                                      int ny) {
  const double w = nx * p.cell_m, hgt = ny * p.cell_m;
  const int n_ctrl = std::max(4, static_cast<int>(std::round(w / 700.0)) + 2);
  const double meander = std::min(p.road.meander_m, 0.3 * hgt);
  std::vector<glm::dvec3> ctrl;
  for (int k = 0; k < n_ctrl; ++k) {
    const double x = w * (0.02 + 0.96 * k / (n_ctrl - 1));
    const double r = 2.0 * hash_unit(layer_seed(p.seed, 10), k, 0) - 1.0;
    ctrl.push_back({x, 0.5 * hgt + meander * r, 0.0});
  }
  const Spline3 flat(ctrl);
  const double ds = 4.0;
  const int n = std::max(2, static_cast<int>(flat.length() / ds) + 1);
  auto sample_h = [&](double x, double y) {
    const int ix = std::clamp(static_cast<int>(x / p.cell_m), 0, nx - 1);
    const int iy = std::clamp(static_cast<int>(y / p.cell_m), 0, ny - 1);
    return static_cast<double>(h[static_cast<std::size_t>(iy) * nx + ix]);
  };
  std::vector<glm::dvec3> pts(n);
  std::vector<double> z(n);
  for (int i = 0; i < n; ++i) {
    pts[i] = flat.at(flat.length() * i / (n - 1));
    // Lakes are crossed on embankments a few metres above the water.
    z[i] = std::max(sample_h(pts[i].x, pts[i].y), p.terrain.water_level_m + 3.0);
  }
  // Two box passes = a triangular filter of the smoothing length.
  const int half = std::max(1, static_cast<int>(p.road.smoothing_m / ds / 2.0));
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<double> prefix(n + 1, 0.0);
    for (int i = 0; i < n; ++i) prefix[i + 1] = prefix[i] + z[i];
    for (int i = 0; i < n; ++i) {
      const int a = std::max(0, i - half), b = std::min(n - 1, i + half);
      z[i] = (prefix[b + 1] - prefix[a]) / (b - a + 1);
    }
  }
  // Control points every ~40 m keep the final spline on the winding curve.
  std::vector<glm::dvec3> out;
  const int stride = 10;
  for (int i = 0; i < n; i += stride) out.push_back({pts[i].x, pts[i].y, z[i]});
  if ((n - 1) % stride != 0) out.push_back({pts[n - 1].x, pts[n - 1].y, z[n - 1]});
  return out;
}

// Distance to the centre line and road height for every cell within `reach` of it.
RoadStamp stamp_road(const Spline3& road_local, int nx, int ny, double cell, double reach) {
  RoadStamp st;
  const std::size_t n = static_cast<std::size_t>(nx) * ny;
  st.dist.assign(n, std::numeric_limits<float>::infinity());
  st.road_z.assign(n, 0.0f);
  const double seg = 8.0;
  const int m = std::max(1, static_cast<int>(std::ceil(road_local.length() / seg)));
  for (int k = 0; k < m; ++k) {
    const glm::dvec3 a = road_local.at(road_local.length() * k / m);
    const glm::dvec3 b = road_local.at(road_local.length() * (k + 1) / m);
    const glm::dvec2 a2(a), ab = glm::dvec2(b) - a2;
    const double len2 = std::max(1e-12, glm::dot(ab, ab));
    const int i0 = std::max(0, static_cast<int>((std::min(a.x, b.x) - reach) / cell));
    const int i1 = std::min(nx - 1, static_cast<int>((std::max(a.x, b.x) + reach) / cell));
    const int j0 = std::max(0, static_cast<int>((std::min(a.y, b.y) - reach) / cell));
    const int j1 = std::min(ny - 1, static_cast<int>((std::max(a.y, b.y) + reach) / cell));
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        const glm::dvec2 c((i + 0.5) * cell, (j + 0.5) * cell);
        const double u = std::clamp(glm::dot(c - a2, ab) / len2, 0.0, 1.0);
        const double d = glm::length(c - (a2 + ab * u));
        const std::size_t idx = static_cast<std::size_t>(j) * nx + i;
        if (d < st.dist[idx]) {
          st.dist[idx] = static_cast<float>(d);
          st.road_z[idx] = static_cast<float>(a.z + (b.z - a.z) * u);
        }
      }
    }
  }
  return st;
}

// Threshold t such that a fraction `f` of `values` lies above t (histogram quantile).
double upper_quantile(const std::vector<float>& values, double f) {
  if (values.empty()) return 1.0;
  constexpr int kBins = 2048;
  std::vector<std::size_t> hist(kBins, 0);
  for (float v : values) hist[std::clamp(static_cast<int>(v * kBins), 0, kBins - 1)]++;
  const double target = f * static_cast<double>(values.size());
  double above = 0.0;
  for (int b = kBins - 1; b >= 0; --b) {
    above += static_cast<double>(hist[b]);
    if (above >= target) return static_cast<double>(b) / kBins;
  }
  return 0.0;
}

}  // namespace

void World::allocate(const WorldParams& params) {
  landmarks_ = std::make_shared<LandmarkCache>();
  start_lighting_ = std::make_shared<StartLighting>();
  params_ = params;
  lighting_ = Lighting(params.sun, params.sky, params.fog);
  cell_ = params.cell_m;
  origin_ = params.origin;
  nx_ = static_cast<int>(std::lround(params.size_m.x / cell_));
  ny_ = static_cast<int>(std::lround(params.size_m.y / cell_));
  const std::size_t n = static_cast<std::size_t>(nx_) * ny_;
  ground_.assign(n, 0.0f);
  surface_.assign(n, 0.0f);
  biome_.assign(n, Biome::Grass);
  albedo_.assign(n, Rgb(0.0f));
}

World::World(const WorldParams& p) {
  allocate(p);
  if (p.level) {
    build_from_level(*p.level);
    return;
  }
  const TerrainParams& t = p.terrain;
  const int ob = octaves_for(t.wavelength_m, cell_);
  const int orr = octaves_for(0.55 * t.wavelength_m, cell_);
  // 1. Raw terrain (local coordinates: cell centres relative to the origin).
  std::vector<float> h(ground_.size());
  std::vector<double> xs(nx_), r0(nx_), r1(nx_), r2(nx_), r3(nx_);
  for (int i = 0; i < nx_; ++i) xs[i] = (i + 0.5) * cell_;
  for (int j = 0; j < ny_; ++j) {
    raw_height_row(p, xs, (j + 0.5) * cell_, ob, orr, r0, r1, r2, &h[cell_index(0, j)]);
  }
  // 2. Road: centre line and grading.
  RoadStamp st;
  const double half_w = 0.5 * p.road.width_m;
  const double inner = half_w + p.road.shoulder_m;
  if (p.road.enabled) {
    const Spline3 local(road_polyline(p, h, nx_, ny_));
    const double reach = inner + p.road.clearance_m + 1.6 * t.amplitude_m;
    st = stamp_road(local, nx_, ny_, cell_, std::min(reach, inner + 250.0));
    std::vector<glm::dvec3> world_pts = local.control_points();
    for (auto& q : world_pts) q += glm::dvec3(origin_, 0.0);
    road_ = Spline3(world_pts);
    const double tan_cut = std::tan(p.road.cutting_slope_deg * std::numbers::pi / 180.0);
    const double tan_emb = std::tan(p.road.embankment_slope_deg * std::numbers::pi / 180.0);
    for (std::size_t k = 0; k < h.size(); ++k) {
      const double d = st.dist[k];
      if (!std::isfinite(d)) continue;
      const double zr = st.road_z[k];
      if (d <= inner) {
        h[k] = static_cast<float>(zr);
      } else if (h[k] > zr) {
        h[k] = static_cast<float>(std::min<double>(h[k], zr + (d - inner) * tan_cut));
      } else {
        h[k] = static_cast<float>(std::max<double>(h[k], zr - (d - inner) * tan_emb));
      }
    }
  }
  // 3. Lakes: water surface replaces the ground below the water level.
  std::vector<std::uint8_t> water(h.size(), 0);
  for (std::size_t k = 0; k < h.size(); ++k) {
    if (h[k] < t.water_level_m) {
      water[k] = 1;
      h[k] = static_cast<float>(t.water_level_m);
    }
  }
  ground_ = h;
  // 4. Biomes, in priority order.
  std::vector<float> forest_mask(h.size(), -1.0f);
  std::vector<float> eligible;
  const std::uint64_t s_forest = layer_seed(p.seed, 20), s_snow = layer_seed(p.seed, 21);
  const std::uint64_t s_field = layer_seed(p.seed, 22), s_sand = layer_seed(p.seed, 23);
  for (int j = 0; j < ny_; ++j) {
    const double yr = (j + 0.5) * cell_;
    fbm_noise_row(s_snow, xs.data(), nx_, yr, 60.0, 1, 0.5, r0.data());
    fbm_noise_row(s_sand, xs.data(), nx_, yr, 35.0, 1, 0.5, r1.data());
    fbm_noise_row(s_forest, xs.data(), nx_, yr, 450.0, 4, 0.5, r2.data());
    for (int i = 0; i < nx_; ++i) {
      const std::size_t k = cell_index(i, j);
      const double x = xs[i], y = yr;
      const double d = p.road.enabled ? st.dist[k] : std::numeric_limits<double>::infinity();
      const glm::dvec3 n = cell_normal(i, j);
      const double slope_deg = std::acos(std::clamp(n.z, -1.0, 1.0)) * 180.0 / std::numbers::pi;
      Biome b = Biome::Grass;
      if (d <= half_w) {
        b = Biome::Asphalt;
      } else if (water[k]) {
        b = Biome::Water;
      } else if (slope_deg > 38.0) {
        b = Biome::Rock;
      } else if (h[k] > t.snow_line_m + 25.0 * (r0[i] - 0.5)) {
        b = Biome::Snow;
      } else if (h[k] < t.water_level_m + 2.0) {
        b = Biome::Sand;  // beaches
      } else if (d > inner && slope_deg < 14.0 &&
                 hash_unit(s_field, static_cast<std::int64_t>(std::floor(x / 170.0)),
                           static_cast<std::int64_t>(std::floor((y + 37.0 * std::floor(x / 170.0)) /
                                                                110.0))) < t.field_fraction &&
                 h[k] < t.water_level_m + 0.45 * t.amplitude_m) {
        b = Biome::Field;
      } else if (r1[i] > 0.93 && slope_deg < 12.0 && d > inner) {
        b = Biome::Sand;  // bunkers
      } else if (d > inner + p.road.clearance_m && slope_deg < 35.0 &&
                 h[k] < t.snow_line_m - 20.0) {
        forest_mask[k] = static_cast<float>(r2[i]);
        eligible.push_back(forest_mask[k]);
      }
      biome_[k] = b;
    }
  }
  // The forest threshold is a quantile, so forest_fraction holds for any seed; the hard
  // threshold gives the sharp forest edge.
  const float thr = static_cast<float>(upper_quantile(eligible, t.forest_fraction));
  const std::uint64_t s_canopy = layer_seed(p.seed, 24), s_tint = layer_seed(p.seed, 25);
  for (int j = 0; j < ny_; ++j) {
    const double yr = (j + 0.5) * cell_;
    fbm_noise_row(s_canopy, xs.data(), nx_, yr, 12.0, 1, 0.5, r0.data());
    fbm_noise_row(s_tint, xs.data(), nx_, yr, 20.0, 1, 0.5, r1.data());
    for (int i = 0; i < nx_; ++i) {
      const std::size_t k = cell_index(i, j);
      float canopy = 0.0f;
      if (forest_mask[k] >= 0.0f && forest_mask[k] >= thr) {
        biome_[k] = Biome::Forest;
        canopy = static_cast<float>(t.canopy_min_m + (t.canopy_max_m - t.canopy_min_m) * r0[i]);
      }
      surface_[k] = ground_[k] + canopy;
      const float tint = biome_[k] == Biome::Water || biome_[k] == Biome::Asphalt
                             ? 1.0f
                             : static_cast<float>(0.85 + 0.3 * r1[i]);
      albedo_[k] = biome_albedo(biome_[k]) * tint;
    }
  }
  finalize();
}

void World::build_from_level(const TerrainLevel& level) {
  ground_ = level.ground_m;
  // Water where the mask says (the heightmap gives its surface), else forest where there is
  // canopy, else plain ground (Grass: the generator's default biome, no further classes are
  // guessed from slope or height).
  for (std::size_t k = 0; k < ground_.size(); ++k) {
    Biome b = Biome::Grass;
    float canopy = 0.0f;
    if (!level.water.empty() && level.water[k] != 0) {
      b = Biome::Water;
    } else if (!level.canopy_m.empty() && level.canopy_m[k] > 0.0f) {
      b = Biome::Forest;
      canopy = level.canopy_m[k];
    }
    biome_[k] = b;
    surface_[k] = ground_[k] + canopy;
    albedo_[k] = level.albedo.empty() ? biome_albedo(b) : level.albedo[k];
  }
  // The far ground continues the level's border: the mean albedo (Rec. 709 luminance) of the
  // edge cells, so that a level does not end in an arbitrary grey ring on the horizon.
  double sum = 0.0;
  std::size_t count = 0;
  for (int j = 0; j < ny_; ++j) {
    for (int i = 0; i < nx_; ++i) {
      if (i != 0 && j != 0 && i != nx_ - 1 && j != ny_ - 1) continue;
      const Rgb& a = albedo_[cell_index(i, j)];
      sum += luminance(a);
      ++count;
    }
  }
  far_albedo_ = static_cast<float>(sum / static_cast<double>(count));
  finalize();
}

World World::flat_test_world(double disc_radius_m, const Rgb& disc_radiance, const Rgb& sky,
                             double size_m, double cell_m) {
  WorldParams p;
  p.size_m = {size_m, size_m};
  p.cell_m = cell_m;
  p.origin = {-0.5 * size_m, -0.5 * size_m};
  p.road.enabled = false;
  p.sun.enabled = false;
  p.sky.model = SkyParams::Model::gradient;
  p.sky.uniform = true;
  p.sky.uniform_radiance = sky;
  World w;
  w.allocate(p);
  // Sun off and a uniform sky give flat ground the radiance albedo * S exactly.
  const Rgb albedo = disc_radiance / sky;
  for (int j = 0; j < w.ny_; ++j) {
    for (int i = 0; i < w.nx_; ++i) {
      const double x = p.origin.x + (i + 0.5) * cell_m, y = p.origin.y + (j + 0.5) * cell_m;
      const bool in = x * x + y * y <= disc_radius_m * disc_radius_m;
      w.albedo_[w.cell_index(i, j)] = in ? albedo : Rgb(0.0f);
    }
  }
  w.far_albedo_ = 0.0f;
  w.finalize();
  return w;
}

void World::finalize() {
  min_surface_ = *std::min_element(surface_.begin(), surface_.end());
  max_surface_ = *std::max_element(surface_.begin(), surface_.end());
  compute_shadow_heights();
  top_radiance_.resize(surface_.size());
  for (int j = 0; j < ny_; ++j) {
    for (int i = 0; i < nx_; ++i) {
      const std::size_t k = cell_index(i, j);
      top_radiance_[k] =
          lighting_.surface_radiance(albedo_[k], cell_normal(i, j), surface_[k] >= shadow_[k]);
    }
  }
  far_radiance_ = lighting_.surface_radiance(Rgb(far_albedo_), {0.0, 0.0, 1.0}, true);
  pyramid_ = HeightPyramid(surface_, nx_, ny_);
}

void World::compute_shadow_heights() {
  shadow_ = shadow_heights(surface_, nx_, ny_, cell_, lighting_.sun_dir(), lighting_.sun_on());
}

bool World::contains_xy(double x, double y) const {
  const glm::dvec2 l = to_local(x, y);
  return l.x >= 0.0 && l.y >= 0.0 && l.x < nx_ * cell_ && l.y < ny_ * cell_;
}

namespace {

double bilinear(const std::vector<float>& a, int nx, int ny, double u, double v) {
  u = std::clamp(u, 0.0, nx - 1.0);
  v = std::clamp(v, 0.0, ny - 1.0);
  const int i = std::min(static_cast<int>(u), std::max(0, nx - 2));
  const int j = std::min(static_cast<int>(v), std::max(0, ny - 2));
  const double fu = u - i, fv = v - j;
  const int i1 = std::min(i + 1, nx - 1), j1 = std::min(j + 1, ny - 1);
  auto h = [&](int ii, int jj) {
    return static_cast<double>(a[static_cast<std::size_t>(jj) * nx + ii]);
  };
  return (h(i, j) * (1 - fu) + h(i1, j) * fu) * (1 - fv) +
         (h(i, j1) * (1 - fu) + h(i1, j1) * fu) * fv;
}

}  // namespace

double World::ground_height(double x, double y) const {
  if (!contains_xy(x, y)) return min_surface_;
  const glm::dvec2 l = to_local(x, y);
  return bilinear(ground_, nx_, ny_, l.x / cell_ - 0.5, l.y / cell_ - 0.5);
}

double World::surface_height(double x, double y) const {
  if (!contains_xy(x, y)) return min_surface_;
  const glm::dvec2 l = to_local(x, y);
  return bilinear(surface_, nx_, ny_, l.x / cell_ - 0.5, l.y / cell_ - 0.5);
}

Biome World::biome_at(double x, double y) const {
  if (!contains_xy(x, y)) return Biome::Grass;
  const glm::dvec2 l = to_local(x, y);
  return cell_biome(std::min(static_cast<int>(l.x / cell_), nx_ - 1),
                    std::min(static_cast<int>(l.y / cell_), ny_ - 1));
}

Rgb World::albedo_at(double x, double y) const {
  if (!contains_xy(x, y)) return Rgb(far_albedo_);
  const glm::dvec2 l = to_local(x, y);
  return cell_albedo(std::min(static_cast<int>(l.x / cell_), nx_ - 1),
                     std::min(static_cast<int>(l.y / cell_), ny_ - 1));
}

bool World::sunlit(const glm::dvec3& p) const {
  if (!lighting_.sun_on()) return false;
  if (!contains_xy(p.x, p.y)) return true;
  const glm::dvec2 l = to_local(p.x, p.y);
  return p.z >= shadow_height(std::min(static_cast<int>(l.x / cell_), nx_ - 1),
                              std::min(static_cast<int>(l.y / cell_), ny_ - 1));
}

glm::dvec3 World::cell_normal(int ix, int iy) const {
  const int i0 = std::max(ix - 1, 0), i1 = std::min(ix + 1, nx_ - 1);
  const int j0 = std::max(iy - 1, 0), j1 = std::min(iy + 1, ny_ - 1);
  const double dzdx =
      (i1 > i0) ? (column_ground(i1, iy) - column_ground(i0, iy)) / ((i1 - i0) * cell_) : 0.0;
  const double dzdy =
      (j1 > j0) ? (column_ground(ix, j1) - column_ground(ix, j0)) / ((j1 - j0) * cell_) : 0.0;
  return glm::normalize(glm::dvec3(-dzdx, -dzdy, 1.0));
}

glm::dvec3 World::face_normal(int ix, int iy, ColumnFace face) const {
  int nbx = ix, nby = iy;
  glm::dvec3 axis(0.0);
  switch (face) {
    case ColumnFace::WallNegX:
      nbx = ix - 1;
      axis = {-1, 0, 0};
      break;
    case ColumnFace::WallPosX:
      nbx = ix + 1;
      axis = {1, 0, 0};
      break;
    case ColumnFace::WallNegY:
      nby = iy - 1;
      axis = {0, -1, 0};
      break;
    case ColumnFace::WallPosY:
      nby = iy + 1;
      axis = {0, 1, 0};
      break;
    default:
      return cell_normal(ix, iy);
  }
  const bool inside = nbx >= 0 && nby >= 0 && nbx < nx_ && nby < ny_;
  const double below = inside ? column_top(nbx, nby) : min_surface_;
  return column_top(ix, iy) - below > cell_ ? axis : cell_normal(ix, iy);
}

Rgb World::wall_radiance(int ix, int iy, ColumnFace face, double z) const {
  if (face == ColumnFace::Top || face == ColumnFace::Inside) return top_radiance(ix, iy);
  return lighting_.surface_radiance(cell_albedo(ix, iy), face_normal(ix, iy, face),
                                    z >= shadow_height(ix, iy));
}

std::uint64_t World::content_hash() const {
  ContentHasher h;
  h.add_value(nx_);
  h.add_value(ny_);
  h.add_value(cell_);
  h.add_vector(ground_);
  h.add_vector(surface_);
  h.add_vector(shadow_);
  h.add_vector(biome_);
  h.add_vector(albedo_);
  h.add_vector(top_radiance_);
  // The road in local coordinates, so an origin shift keeps the fingerprint.
  for (const auto& q : road_.control_points()) {
    // Millimetre rounding: q - origin differs in the last bits when the origin is far away.
    const std::int64_t l[3] = {std::llround((q.x - origin_.x) * 1e3),
                               std::llround((q.y - origin_.y) * 1e3), std::llround(q.z * 1e3)};
    h.add_bytes(l, sizeof(l));
  }
  return h.value();
}

struct World::LandmarkCache {
  std::once_flag once;
  WorldLandmarks landmarks;
};

const WorldLandmarks& World::landmarks() const {
  // The cache is created with the world (allocate()); a moved-from world has none.
  std::call_once(landmarks_->once, [this] { landmarks_->landmarks = find_landmarks(*this); });
  return landmarks_->landmarks;
}

struct World::StartLighting {
  std::once_flag once;
  std::unique_ptr<LightingModel> model;
  const LightingState* state = nullptr;
};

const LightingState& World::start_lighting() const {
  std::call_once(start_lighting_->once, [this] {
    start_lighting_->model = std::make_unique<LightingModel>(*this);
    start_lighting_->state = &start_lighting_->model->state_at(0.0);
  });
  return *start_lighting_->state;
}

}  // namespace ambisim
