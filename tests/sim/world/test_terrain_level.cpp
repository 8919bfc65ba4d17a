// Imported levels (terrain_level.h): heights, orientation, biomes and errors read back from
// tiny PNGs written with libpng (sim/base/png_codec.h), and captures over them against the
// analytic disc oracle of tests/sim/render/test_capture.cpp and the procedural flat world.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <numbers>
#include <string>

#include <glm/geometric.hpp>

#include "sim/base/json_reader.h"
#include "sim/base/png_codec.h"
#include "sim/colour/cielab.h"
#include "sim/render/capture.h"
#include "sim/world/level_export.h"
#include "sim/world/terrain_level.h"
#include "sim/world/world.h"

using namespace ambisim;

namespace {

PngSamples image(int w, int h, int channels, int depth) {
  return PngSamples::blank(w, h, channels, depth);
}

void set(PngSamples& img, int x, int y, std::uint16_t v, int c = 0) {
  img.samples[(static_cast<std::size_t>(y) * img.width + x) * img.channels + c] = v;
}

// A level whose files live in memory under "levels/t/<name>", next to "dir/scene.json".
struct MemoryLevel {
  std::map<std::string, std::string> files;
  nlohmann::json doc = nlohmann::json::object();

  void add(const std::string& key, const std::string& name, std::string bytes) {
    files["dir/levels/t/" + name] = std::move(bytes);
    doc[key] = "levels/t/" + name;
  }
  TerrainLevel parse() const {
    ObjectReader r(doc, "dir/scene.json", "/world/level");
    return parse_terrain_level(
        r, [this](ObjectReader& rr, const std::string& key, const std::string& path) {
          const auto it = files.find(path);
          if (it == files.end()) rr.fail(key, "no such file: " + path);
          return it->second;
        });
  }
};

// The error of parsing `level`, or "" if it parsed.
std::string error_of(const MemoryLevel& level, std::string* json_path = nullptr) {
  try {
    level.parse();
  } catch (const InputError& e) {
    if (json_path != nullptr) *json_path = e.json_path();
    return e.what();
  }
  return "";
}

WorldParams params_for(const TerrainLevel& level, glm::dvec2 origin = {0.0, 0.0}) {
  WorldParams p;
  p.level = std::make_shared<TerrainLevel>(level);
  p.cell_m = level.cell_m;
  p.size_m = {level.nx * level.cell_m, level.ny * level.cell_m};
  p.origin = origin;
  p.road.enabled = false;
  return p;
}

// Sun off and a uniform sky S: flat ground of albedo a has radiance a S exactly.
void oracle_lighting(WorldParams& p, const Rgb& sky) {
  p.sun.enabled = false;
  p.sky.model = SkyParams::Model::gradient;
  p.sky.uniform = true;
  p.sky.uniform_radiance = sky;
}

// Irradiance of a cube map on a plane with unit normal n: sum L max(0, n.w) dOmega.
glm::dvec3 irradiance(const CubeMap& m, const glm::dvec3& n) {
  glm::dvec3 e(0.0);
  for (int f = 0; f < kCubeFaces; ++f) {
    for (int j = 0; j < m.size; ++j) {
      for (int i = 0; i < m.size; ++i) {
        const glm::dvec3 w = cube_texel_direction(static_cast<CubeFace>(f), m.size, i, j);
        const double c = glm::dot(n, w);
        if (c > 0.0) {
          e += glm::dvec3(m.at(static_cast<CubeFace>(f), i, j)) *
               (c * cube_texel_solid_angle(m.size, i, j));
        }
      }
    }
  }
  return e;
}

// IEC 61966-2-1 sRGB decoding, written out here independently of sim/colour.
double srgb_to_linear(int code) {
  const double c = code / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

}  // namespace

TEST_CASE("level: a step reads back exactly at cell centres, row 0 north, shadows east of it",
          "[level]") {
  // 64 x 8 cells of 2 m: the west half high, the east half low, and each row 10 codes above
  // the one south of it, so a flipped image would show.
  const int nx = 64, ny = 8;
  PngSamples h = image(nx, ny, 1, 16);
  auto code = [&](int i, int j) {
    return static_cast<std::uint16_t>((i < nx / 2 ? 60000 : 1000) + 10 * (ny - 1 - j));
  };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) set(h, i, j, code(i, j));
  }
  MemoryLevel m;
  m.add("heightmap", "h.png", encode_png(h));
  m.doc["cell_m"] = 2.0;
  m.doc["height_scale_m"] = 50.0;
  m.doc["height_offset_m"] = 10.0;
  const TerrainLevel level = m.parse();
  REQUIRE(level.nx == nx);
  REQUIRE(level.ny == ny);
  WorldParams p = params_for(level, {100.0, -50.0});
  p.sun.elevation_deg = 45.0;
  p.sun.azimuth_deg = 270.0;  // in the west: the cliff's shadow falls east
  p.sky.model = SkyParams::Model::gradient;
  const World w(p);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int iy = ny - 1 - j;
      const float expect = static_cast<float>(10.0 + code(i, j) / 65535.0 * 50.0);
      // Exact: the cell-centre value is the decoded sample, bilinear weights 1 and 0.
      const double x = 100.0 + (i + 0.5) * 2.0, y = -50.0 + (iy + 0.5) * 2.0;
      REQUIRE(w.column_ground(i, iy) == expect);
      REQUIRE(w.ground_height(x, y) == static_cast<double>(expect));
      REQUIRE(w.cell_biome(i, iy) == Biome::Grass);
    }
  }
  // The cliff is 45.0 m (60000 - 1000 codes of 50/65535 m); at 45 deg its shadow on the low
  // ground reaches 45 m east of the edge at x = 164. Shadow-map discretisation: one cell.
  const double top = 10.0 + 60000 / 65535.0 * 50.0, low = 10.0 + 1000 / 65535.0 * 50.0;
  const double reach = top - low;
  constexpr double kShadowEdgeTol = 2.0;  // m, one cell
  const double y = -50.0 + 4.5 * 2.0;
  for (double d = 1.0; d < 60.0; d += 2.0) {
    const glm::dvec3 q(164.0 + d, y, w.ground_height(164.0 + d, y) + 0.01);
    INFO("d = " << d);
    if (d < reach - kShadowEdgeTol) CHECK_FALSE(w.sunlit(q));
    if (d > reach + kShadowEdgeTol) CHECK(w.sunlit(q));
  }
  // The high plateau is lit everywhere, west of the edge.
  for (double x = 101.0; x < 164.0; x += 4.0) CHECK(w.sunlit({x, y, top + 0.01}));
  // Occlusion: a capture beside the foot of the cliff sees less sky than one 50 m out, and
  // the low ground's radiance is the same wherever its sky is not blocked.
  const CubeMap near = capture(w, {167.0, y, low + 1.0}, 32);
  const CubeMap far = capture(w, {220.0, y, low + 1.0}, 32);
  CHECK(irradiance(near, {0, 0, 1}).y < irradiance(far, {0, 0, 1}).y);
}

TEST_CASE("level: a plane is an infinite Lambertian plane, RAW and PNG agree", "[level]") {
  const int n = 48;
  const std::uint16_t v = 32768;
  PngSamples h = image(n, n, 1, 16), a = image(n, n, 3, 8);
  std::string raw;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      set(h, i, j, v);
      for (int c = 0; c < 3; ++c) set(a, i, j, 128, c);
      raw.push_back(static_cast<char>(v & 0xFF));  // little-endian, as Unity writes it
      raw.push_back(static_cast<char>(v >> 8));
    }
  }
  MemoryLevel m;
  m.add("heightmap", "h.png", encode_png(h));
  m.add("albedo", "a.png", encode_png(a));
  m.doc["cell_m"] = 1.0;
  m.doc["height_scale_m"] = 100.0;
  m.doc["height_offset_m"] = -20.0;
  const TerrainLevel level = m.parse();
  const double z0 = -20.0 + v / 65535.0 * 100.0;
  MemoryLevel mr = m;
  mr.add("heightmap", "h.raw", raw);
  mr.doc["heightmap_size"] = {n, n};
  const TerrainLevel level_raw = mr.parse();
  CHECK(level_raw.ground_m == level.ground_m);
  CHECK(level_raw.content_hash == level.content_hash);

  const Rgb sky{1.0f, 1.0f, 1.0f};
  WorldParams p = params_for(level, {-24.0, -24.0});
  oracle_lighting(p, sky);
  const World w(p);
  const double albedo = srgb_to_linear(128);
  CHECK(w.cell_albedo(3, 5).x == Approx(albedo).epsilon(1e-6));
  CHECK(w.far_ground_height() == Approx(z0).epsilon(1e-6));
  CHECK(w.far_ground_albedo() == Approx(albedo).epsilon(1e-6));
  for (double dz : {1.0, 5.0, 20.0}) {
    const CubeMap c = capture(w, {0.0123, 0.0071, z0 + dz}, 64);
    // Ground below, continued by the far ground of the border's albedo: pi a S downward; the
    // sky alone upward, pi S. Cube quadrature of the clamped cosine: 8.0e-5 (test_capture).
    constexpr double kPlaneTol = 2e-4;
    INFO("dz = " << dz);
    CHECK(irradiance(c, {0, 0, -1}).y ==
          Approx(std::numbers::pi * albedo * sky.y).epsilon(kPlaneTol));
    CHECK(irradiance(c, {0, 0, 1}).y == Approx(std::numbers::pi * sky.y).epsilon(kPlaneTol));
  }
}

TEST_CASE("level: a disc of another albedo on black ground matches the disc oracle", "[level]") {
  // The existing oracle's scene (tests/sim/render/test_capture.cpp), as images: 512 x 512
  // cells of 1/16 m, a disc of radius 6 m centred on the grid, albedo sRGB (200, 150, 90).
  const int n = 512;
  const double cell = 0.0625, r = 6.0;
  const int code[3] = {200, 150, 90};
  PngSamples h = image(n, n, 1, 16), a = image(n, n, 3, 8);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double x = -16.0 + (i + 0.5) * cell, y = -16.0 + (n - 1 - j + 0.5) * cell;
      if (x * x + y * y > r * r) continue;
      for (int c = 0; c < 3; ++c) set(a, i, j, static_cast<std::uint16_t>(code[c]), c);
    }
  }
  MemoryLevel m;
  m.add("heightmap", "h.png", encode_png(h));
  m.add("albedo", "a.png", encode_png(a));
  m.doc["cell_m"] = cell;
  m.doc["height_scale_m"] = 10.0;
  const Rgb sky{1.0f, 1.0f, 1.0f};
  WorldParams p = params_for(m.parse(), {-16.0, -16.0});
  oracle_lighting(p, sky);
  const World w(p);
  const Rgb disc(static_cast<float>(srgb_to_linear(code[0])),
                 static_cast<float>(srgb_to_linear(code[1])),
                 static_cast<float>(srgb_to_linear(code[2])));
  const World flat = World::flat_test_world(r, disc, sky, 32.0, cell);
  REQUIRE(w.far_ground_albedo() == 0.0f);  // the black border continues beyond the grid
  for (double hgt : {2.0, 6.0, 12.0}) {
    const glm::dvec3 at(0.0123, 0.0071, hgt);
    const CubeMap c = capture(w, at, 64), cf = capture(flat, at, 64);
    const glm::dvec3 down = irradiance(c, {0, 0, -1}), down_flat = irradiance(cf, {0, 0, -1});
    INFO("h = " << hgt);
    // The same cells as the procedural oracle world (albedo from sRGB codes in float): the
    // captures agree to float rounding of the albedo; measured: identical.
    constexpr double kFlatWorldTol = 1e-5;
    for (int k = 0; k < 3; ++k) CHECK(down[k] == Approx(down_flat[k]).epsilon(kFlatWorldTol));
    // The closed form pi L R^2 / (R^2 + h^2) of a Lambertian disc seen from above on its
    // axis; the same tolerance as the oracle test (64^2 quadrature of the disc's edge).
    const double expect = std::numbers::pi * r * r / (r * r + hgt * hgt);
    constexpr double kClosedFormTol = 6e-3;
    for (int k = 0; k < 3; ++k) CHECK(down[k] == Approx(expect * disc[k]).epsilon(kClosedFormTol));
  }
}

TEST_CASE("level: water and canopy masks give the biomes and the canopy height", "[level]") {
  const int n = 4;
  PngSamples h = image(n, n, 1, 16), canopy = image(n, n, 1, 8), water = image(n, n, 1, 8);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) set(h, i, j, 6553);  // 10.0 m with a scale of 100 m
  }
  set(canopy, 1, 0, 255);  // pixel (1, 0): row 0 is north, so cell (1, 3)
  set(canopy, 2, 3, 128);  // cell (2, 0)
  set(water, 0, 3, 1);     // cell (0, 0)
  set(canopy, 0, 3, 255);  // water wins over canopy
  MemoryLevel m;
  m.add("heightmap", "h.png", encode_png(h));
  m.add("canopy", "c.png", encode_png(canopy));
  m.add("water", "w.png", encode_png(water));
  m.doc["cell_m"] = 4.0;
  m.doc["height_scale_m"] = 100.0;
  m.doc["canopy_scale_m"] = 30.0;
  const World w(params_for(m.parse()));
  const float ground = static_cast<float>(6553 / 65535.0 * 100.0);
  CHECK(w.cell_biome(1, 3) == Biome::Forest);
  CHECK(w.column_top(1, 3) == ground + static_cast<float>(255 / 255.0 * 30.0));
  CHECK(w.cell_biome(2, 0) == Biome::Forest);
  CHECK(w.column_top(2, 0) == ground + static_cast<float>(128 / 255.0 * 30.0));
  CHECK(w.cell_biome(0, 0) == Biome::Water);
  CHECK(w.column_top(0, 0) == ground);
  CHECK(w.cell_albedo(0, 0) == biome_albedo(Biome::Water));
  CHECK(w.cell_biome(3, 3) == Biome::Grass);
  CHECK(w.column_top(3, 3) == ground);
  CHECK(w.road().empty());
}

TEST_CASE("level: the content hash follows the images' bytes", "[level]") {
  PngSamples h = image(8, 8, 1, 16), a = image(8, 8, 3, 8);
  MemoryLevel m;
  m.add("heightmap", "h.png", encode_png(h));
  m.add("albedo", "a.png", encode_png(a));
  m.doc["cell_m"] = 2.0;
  m.doc["height_scale_m"] = 100.0;
  const TerrainLevel l0 = m.parse();
  set(a, 5, 2, 1, 1);
  m.add("albedo", "a.png", encode_png(a));
  const TerrainLevel l1 = m.parse();
  set(h, 0, 7, 1);
  m.add("heightmap", "h.png", encode_png(h));
  const TerrainLevel l2 = m.parse();
  CHECK(l0.content_hash != l1.content_hash);
  CHECK(l1.content_hash != l2.content_hash);
  CHECK(World(params_for(l0)).content_hash() != World(params_for(l1)).content_hash());
  // Same bytes, same world: byte-identical arrays.
  CHECK(World(params_for(l2)).content_hash() == World(params_for(m.parse())).content_hash());
}

TEST_CASE("level: bad files and keys are InputErrors naming the file and the JSON path",
          "[level]") {
  PngSamples h16 = image(8, 8, 1, 16), h8 = image(8, 8, 1, 8), a = image(8, 8, 3, 8);
  PngSamples a_small = image(8, 4, 3, 8);
  auto base = [&] {
    MemoryLevel m;
    m.add("heightmap", "h.png", encode_png(h16));
    m.doc["cell_m"] = 2.0;
    m.doc["height_scale_m"] = 100.0;
    return m;
  };
  REQUIRE(error_of(base()).empty());
  struct Case {
    const char* what;
    MemoryLevel level;
    const char* path;
    const char* message;
  };
  std::vector<Case> cases;
  {
    MemoryLevel m = base();
    m.add("heightmap", "h.png", encode_png(h8));
    cases.push_back({"8-bit heightmap", m, "/world/level/heightmap", "8-bit"});
  }
  {
    MemoryLevel m = base();
    m.add("heightmap", "h.png", "GIF89a not a png at all");
    cases.push_back({"not a PNG", m, "/world/level/heightmap", "not a PNG file"});
  }
  {
    MemoryLevel m = base();
    const std::string bytes = encode_png(h16);
    m.add("heightmap", "h.png", bytes.substr(0, bytes.size() / 2));
    cases.push_back({"truncated", m, "/world/level/heightmap", "truncated"});
  }
  {
    MemoryLevel m = base();
    m.add("albedo", "a.png", encode_png(a_small));
    cases.push_back({"sizes disagree", m, "/world/level/albedo", "the heightmap is 8 x 8"});
  }
  {
    MemoryLevel m = base();
    m.add("heightmap", "h.raw", std::string(127, '\0'));
    m.doc["heightmap_size"] = {8, 8};
    cases.push_back({"RAW byte count", m, "/world/level/heightmap", "127 bytes"});
  }
  {
    MemoryLevel m = base();
    m.doc["albdo"] = "levels/t/a.png";
    cases.push_back({"unknown key", m, "/world/level/albdo", "unknown"});
  }
  {
    MemoryLevel m = base();
    m.doc["cell_m"] = 0.0;
    cases.push_back({"cell_m 0", m, "/world/level/cell_m", "> 0"});
  }
  {
    MemoryLevel m = base();
    m.doc["heightmap"] = "levels/t/missing.png";
    cases.push_back({"missing", m, "/world/level/heightmap", "no such file"});
  }
  {
    MemoryLevel m = base();
    m.add("albedo", "a.png", encode_png(h16));
    cases.push_back({"grey albedo", m, "/world/level/albedo", "RGB or RGBA"});
  }
  for (const Case& c : cases) {
    INFO(c.what);
    std::string path;
    const std::string e = error_of(c.level, &path);
    CHECK(path == c.path);
    CHECK(e.find("dir/scene.json") == 0);
    CHECK(e.find(c.message) != std::string::npos);
    CHECK(e.find('\n') == std::string::npos);
    INFO(e);
  }
}

TEST_CASE("level: an exported piece of a procedural world imports back within quantisation",
          "[level]") {
  WorldParams wp;
  wp.size_m = {512.0, 512.0};
  wp.cell_m = 2.0;
  wp.seed = 3;  // tests/data/small_drive.json's world: forest in the north
  wp.road.enabled = false;
  {
    // Lakes on the lowest 10 % of the ground, so the water mask has something to carry.
    const World dry(wp);
    std::vector<float> g(dry.nx() * dry.ny());
    for (int iy = 0; iy < dry.ny(); ++iy) {
      for (int ix = 0; ix < dry.nx(); ++ix) g[dry.cell_index(ix, iy)] = dry.column_ground(ix, iy);
    }
    std::nth_element(g.begin(), g.begin() + g.size() / 10, g.end());
    wp.terrain.water_level_m = g[g.size() / 10];
  }
  const World src(wp);
  const ExportedLevel ex = export_level(src, {0.0, 0.0}, {512.0, 512.0}, 1);
  REQUIRE(ex.heightmap.width == 256);
  REQUIRE(ex.heightmap.height == 256);
  MemoryLevel m;
  m.add("heightmap", "height.png", encode_png(ex.heightmap));
  m.add("albedo", "albedo.png", encode_png(ex.albedo));
  m.add("canopy", "canopy.png", encode_png(ex.canopy));
  m.add("water", "water.png", encode_png(ex.water));
  const nlohmann::json object = ex.level_object("levels/t");
  for (const auto& [k, v] : object.items()) {
    if (!m.doc.contains(k)) m.doc[k] = v;
  }
  const World w(params_for(m.parse(), ex.origin));
  // Heights: half a code of the 16-bit range (plus float rounding); canopy: half an 8-bit
  // code of its scale; albedo: half an 8-bit sRGB code, measured back in sRGB.
  const double kHeightTol = 0.5 * ex.height_scale_m / 65535.0 + 1e-4;
  const double kCanopyTol = 0.5 * ex.canopy_scale_m / 255.0 + 1e-4;
  constexpr double kSrgbCodeTol = 0.5 / 255.0 + 1e-6;
  int water = 0, forest = 0;
  double worst_h = 0.0;
  for (int iy = 0; iy < 256; ++iy) {
    for (int ix = 0; ix < 256; ++ix) {
      const int sx = ix, sy = iy;  // the same cell of the source
      const double dh = std::abs(w.column_ground(ix, iy) - src.column_ground(sx, sy));
      worst_h = std::max(worst_h, dh);
      REQUIRE(dh <= kHeightTol);
      const Biome b = src.cell_biome(sx, sy);
      const Biome expect = b == Biome::Water || b == Biome::Forest ? b : Biome::Grass;
      REQUIRE(w.cell_biome(ix, iy) == expect);
      water += b == Biome::Water;
      forest += b == Biome::Forest;
      if (b == Biome::Forest) {
        REQUIRE(std::abs((w.column_top(ix, iy) - w.column_ground(ix, iy)) -
                         (src.column_top(sx, sy) - src.column_ground(sx, sy))) <= kCanopyTol);
      }
      for (int c = 0; c < 3; ++c) {
        REQUIRE(std::abs(srgb_encode(w.cell_albedo(ix, iy)[c]) -
                         srgb_encode(src.cell_albedo(sx, sy)[c])) <= kSrgbCodeTol);
      }
    }
  }
  INFO("worst height error " << worst_h << " m of " << kHeightTol);
  CHECK(water > 0);
  CHECK(forest > 0);
}
