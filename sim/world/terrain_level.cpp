#include "sim/world/terrain_level.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "sim/base/hash.h"
#include "sim/base/json_reader.h"
#include "sim/base/png_codec.h"
#include "sim/colour/cielab.h"

namespace ambisim {
namespace {

// The world's own limits (world_params.cpp): 16384 cells a side, 2^26 cells in all.
constexpr int kMaxSide = 16384;
constexpr double kMaxCells = 67108864.0;

std::string resolve(const ObjectReader& r, const std::string& name) {
  namespace fs = std::filesystem;
  const fs::path p(name);
  if (p.is_absolute()) return p.lexically_normal().string();
  return (fs::path(r.file()).parent_path() / p).lexically_normal().string();
}

bool is_raw_name(const std::string& name) {
  std::string ext = std::filesystem::path(name).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".raw" || ext == ".r16";
}

struct NamedFile {
  std::string key;
  std::string path;  // resolved
  std::string bytes;
};

NamedFile read_named(ObjectReader& r, const std::string& key, const LevelFileReader& read) {
  const std::string name = r.string(key);
  if (name.empty()) r.fail(key, "must name an image file");
  NamedFile f{key, resolve(r, name), {}};
  f.bytes = read(r, key, f.path);
  return f;
}

PngSamples decode(ObjectReader& r, const NamedFile& f) {
  PngDecodeResult d = decode_png(f.bytes);
  if (!d.image) r.fail(f.key, f.path + ": " + d.error);
  return std::move(*d.image);
}

std::string dims(int w, int h) { return std::to_string(w) + " x " + std::to_string(h); }

// Pixel (i, j), row 0 north, to the cell index (iy = 0 south).
std::size_t cell_of(int nx, int ny, int i, int j) {
  return static_cast<std::size_t>(ny - 1 - j) * static_cast<std::size_t>(nx) + i;
}

void check_grid(ObjectReader& r, const std::string& key, const std::string& path, int w, int h) {
  if (w < 2 || h < 2) r.fail(key, path + ": " + dims(w, h) + " pixels: at least 2 x 2 needed");
  if (w > kMaxSide || h > kMaxSide) {
    r.fail(key, path + ": " + dims(w, h) + " pixels: at most 16384 a side");
  }
  if (static_cast<double>(w) * h > kMaxCells) {
    r.fail(key, path + ": " + dims(w, h) + " pixels: at most 67108864 (8192 x 8192) in all");
  }
}

void check_same_size(ObjectReader& r, const NamedFile& f, const PngSamples& img,
                     const TerrainLevel& level) {
  if (img.width != level.nx || img.height != level.ny) {
    r.fail(f.key, f.path + ": " + dims(img.width, img.height) + " pixels, but the heightmap is " +
                      dims(level.nx, level.ny));
  }
}

// The height convention of Unity (TerrainData: a sample s / 65535 of the terrain's height
// size.y, above the terrain's position) and Unreal (Landscape: (s - 32768) / 128 * scale.z
// cm, i.e. height_scale_m = 65535 / 12800 * scale.z and height_offset_m = -2.56 * scale.z):
// height = offset + s / 65535 * scale.
float height_of(std::uint16_t s, double scale_m, double offset_m) {
  return static_cast<float>(offset_m + static_cast<double>(s) / 65535.0 * scale_m);
}

void read_heightmap(ObjectReader& r, const LevelFileReader& read, double scale_m, double offset_m,
                    TerrainLevel& level) {
  const NamedFile f = read_named(r, "heightmap", read);
  if (is_raw_name(f.path)) {
    if (!r.has("heightmap_size")) {
      r.fail("heightmap", f.path + ": a RAW heightmap needs /heightmap_size [width, height]");
    }
    const std::vector<double> size = r.numbers("heightmap_size", Range::closed(1.0, 1e9));
    if (size.size() != 2 || size[0] != std::floor(size[0]) || size[1] != std::floor(size[1])) {
      r.fail("heightmap_size", "must be two whole numbers [width, height] in pixels");
    }
    const int w = static_cast<int>(std::min(size[0], 1e6));
    const int h = static_cast<int>(std::min(size[1], 1e6));
    check_grid(r, "heightmap_size", f.path, w, h);
    const std::size_t want = static_cast<std::size_t>(w) * h * 2;
    if (f.bytes.size() != want) {
      r.fail("heightmap", f.path + ": " + std::to_string(f.bytes.size()) + " bytes, but a " +
                              dims(w, h) + " RAW 16-bit heightmap has " + std::to_string(want));
    }
    level.nx = w;
    level.ny = h;
    level.ground_m.resize(static_cast<std::size_t>(w) * h);
    const auto* b = reinterpret_cast<const unsigned char*>(f.bytes.data());
    for (int j = 0; j < h; ++j) {
      for (int i = 0; i < w; ++i) {
        const std::size_t k = (static_cast<std::size_t>(j) * w + i) * 2;
        // Little-endian, as Unity's RAW export (Byte Order: Windows) writes it.
        const auto s = static_cast<std::uint16_t>(b[k] | (b[k + 1] << 8));
        level.ground_m[cell_of(w, h, i, j)] = height_of(s, scale_m, offset_m);
      }
    }
    return;
  }
  if (r.has("heightmap_size")) r.fail("heightmap_size", "only for a RAW heightmap (.raw, .r16)");
  const PngSamples img = decode(r, f);
  if (img.channels != 1 || img.palette) {
    r.fail("heightmap", f.path + ": a heightmap must be greyscale (one 16-bit channel), got " +
                            std::to_string(img.channels) + " channels");
  }
  if (img.bit_depth != 16) {
    r.fail("heightmap", f.path + ": " + std::to_string(img.bit_depth) +
                            "-bit: a heightmap must be 16-bit greyscale");
  }
  check_grid(r, "heightmap", f.path, img.width, img.height);
  level.nx = img.width;
  level.ny = img.height;
  level.ground_m.resize(static_cast<std::size_t>(level.nx) * level.ny);
  for (int j = 0; j < level.ny; ++j) {
    for (int i = 0; i < level.nx; ++i) {
      level.ground_m[cell_of(level.nx, level.ny, i, j)] =
          height_of(img.at(i, j), scale_m, offset_m);
    }
  }
}

void read_albedo(ObjectReader& r, const LevelFileReader& read, TerrainLevel& level) {
  const NamedFile f = read_named(r, "albedo", read);
  const PngSamples img = decode(r, f);
  if (img.channels != 3 && img.channels != 4) {
    r.fail("albedo", f.path + ": an albedo map must be RGB or RGBA, got " +
                         std::to_string(img.channels) + " channel(s)");
  }
  if (img.bit_depth != 8) r.fail("albedo", f.path + ": an albedo map must be 8-bit sRGB");
  check_same_size(r, f, img, level);
  // Decode each of the 256 codes once: sRGB (IEC 61966-2-1) -> linear.
  float lut[256];
  for (int v = 0; v < 256; ++v) lut[v] = static_cast<float>(srgb_decode(v / 255.0));
  level.albedo.resize(level.ground_m.size());
  for (int j = 0; j < level.ny; ++j) {
    for (int i = 0; i < level.nx; ++i) {
      level.albedo[cell_of(level.nx, level.ny, i, j)] =
          Rgb(lut[img.at(i, j, 0)], lut[img.at(i, j, 1)], lut[img.at(i, j, 2)]);
    }
  }
}

void read_canopy(ObjectReader& r, const LevelFileReader& read, double scale_m,
                 TerrainLevel& level) {
  const NamedFile f = read_named(r, "canopy", read);
  const PngSamples img = decode(r, f);
  if (img.channels != 1 || img.palette) {
    r.fail("canopy", f.path + ": a canopy map must be greyscale (8 or 16 bit)");
  }
  check_same_size(r, f, img, level);
  level.canopy_m.resize(level.ground_m.size());
  const double max = img.max_value();
  for (int j = 0; j < level.ny; ++j) {
    for (int i = 0; i < level.nx; ++i) {
      level.canopy_m[cell_of(level.nx, level.ny, i, j)] =
          static_cast<float>(img.at(i, j) / max * scale_m);
    }
  }
}

void read_water(ObjectReader& r, const LevelFileReader& read, TerrainLevel& level) {
  const NamedFile f = read_named(r, "water", read);
  const PngSamples img = decode(r, f);
  if (img.channels != 1 || img.palette || img.bit_depth != 8) {
    r.fail("water", f.path + ": a water mask must be 8-bit greyscale");
  }
  check_same_size(r, f, img, level);
  level.water.resize(level.ground_m.size());
  for (int j = 0; j < level.ny; ++j) {
    for (int i = 0; i < level.nx; ++i) {
      level.water[cell_of(level.nx, level.ny, i, j)] = img.at(i, j) != 0 ? 1 : 0;
    }
  }
}

}  // namespace

std::string read_level_file_from_disk(ObjectReader& r, const std::string& key,
                                      const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const auto status = fs::status(path, ec);
  if (ec || !fs::exists(status)) r.fail(key, "no such file: " + path);
  if (fs::is_directory(status)) r.fail(key, "is a directory, not an image file: " + path);
  std::ifstream in(path, std::ios::binary);
  if (!in) r.fail(key, "cannot be opened for reading: " + path);
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) r.fail(key, "read error: " + path);
  return buffer.str();
}

TerrainLevel parse_terrain_level(ObjectReader& r, const LevelFileReader& read) {
  TerrainLevel level;
  // Keys first (a typo is reported before any file is read), files after.
  level.cell_m = r.number("cell_m", Range{0.0, 64.0, true, false});
  const double scale_m = r.number("height_scale_m", Range{0.0, 1e5, true, false});
  const double offset_m = r.number("height_offset_m", 0.0, Range::closed(-1e5, 1e5));
  const bool has_canopy = r.has("canopy");
  double canopy_scale_m = 0.0;
  if (has_canopy) {
    canopy_scale_m = r.number("canopy_scale_m", Range::closed(0.0, 200.0));
  } else if (r.has("canopy_scale_m")) {
    r.fail("canopy_scale_m", "only with a canopy map (/canopy)");
  } else {
    (void)r.raw("canopy_scale_m");  // listed among the valid keys
  }
  // Every key is read (and checked for its type) before any file is: a typo is reported
  // without touching the disk.
  (void)r.string("heightmap");
  // (Reads with a fallback, so that an unknown key's message lists the optional ones too.)
  for (const char* k : {"albedo", "canopy", "water"}) (void)r.string(k, "");
  if (r.has("heightmap_size")) {
    (void)r.numbers("heightmap_size", Range::closed(1.0, 1e9));
  } else {
    (void)r.raw("heightmap_size");
  }
  r.finish();
  const bool has_albedo = r.has("albedo"), has_water = r.has("water");
  read_heightmap(r, read, scale_m, offset_m, level);
  if (has_albedo) read_albedo(r, read, level);
  if (has_canopy) read_canopy(r, read, canopy_scale_m, level);
  if (has_water) read_water(r, read, level);
  ContentHasher h;
  h.add_value(level.nx);
  h.add_value(level.ny);
  h.add_value(level.cell_m);
  h.add_vector(level.ground_m);
  h.add_vector(level.canopy_m);
  h.add_vector(level.water);
  h.add_vector(level.albedo);
  level.content_hash = h.value();
  return level;
}

}  // namespace ambisim
