#pragma once
// The world: a heightfield (generated, or imported from a game's level: terrain_level.h) of square
// cells ("columns") with biomes, a forest canopy layer, lakes and a graded motorway, lit by the sun
// and sky (sim/world/lighting.h).
//
// Frames: world x east, y north, z up, metres. The grid's south-west corner is at
// params.origin; all grid math is done relative to it in double, so shifting the origin
// (even by 1e6 m) leaves every generated array bit-identical.
//
// The solid surface for rendering is a set of columns: cell (ix, iy) covers
// [x0, x0 + cell) x [y0, y0 + cell) and is solid from -infinity up to its surface height
// (ground + canopy). Beyond the grid the world is an infinite flat "far ground" plane at the
// lowest surface height, neutral grey, unshadowed; above it only sky.
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "sim/colour/rgb.h"
#include "sim/world/biome.h"
#include "sim/world/height_pyramid.h"
#include "sim/world/lighting.h"
#include "sim/world/spline.h"
#include "sim/world/world_params.h"

namespace ambisim {

// Faces of a column through which a ray enters it (the "hit surface" is (cell, face)).
enum class ColumnFace : std::uint8_t { Top = 0, WallNegX, WallPosX, WallNegY, WallPosY, Inside };

struct WorldLandmarks;
struct LightingState;

class World {
 public:
  // Generates the world (or builds it from params.level); deterministic and bit-identical
  // for equal params.
  explicit World(const WorldParams& params);

  // Analytic oracle world (sun off, uniform sky of radiance `sky`): flat ground at z = 0, a
  // disc of radius `disc_radius_m` centred on the world origin (0, 0) whose outgoing radiance
  // is exactly `disc_radiance`, black ground elsewhere (also beyond the grid). The grid is
  // size_m x size_m centred on (0, 0).
  static World flat_test_world(double disc_radius_m, const Rgb& disc_radiance, const Rgb& sky,
                               double size_m = 64.0, double cell_m = 0.125);

  const WorldParams& params() const { return params_; }
  const Lighting& lighting() const { return lighting_; }

  // Grid geometry.
  int nx() const { return nx_; }
  int ny() const { return ny_; }
  double cell_m() const { return cell_; }
  glm::dvec2 min_xy() const { return origin_; }
  glm::dvec2 max_xy() const { return origin_ + glm::dvec2(nx_ * cell_, ny_ * cell_); }
  bool contains_xy(double x, double y) const;

  // Heights (bilinear between cell centres, clamped at the border); outside the grid: the
  // far-ground height. ground_height excludes the canopy; lakes report the water surface.
  double ground_height(double x, double y) const;
  double surface_height(double x, double y) const;
  // Nearest-cell queries; outside the grid: Grass / the far-ground grey.
  Biome biome_at(double x, double y) const;
  Rgb albedo_at(double x, double y) const;
  // Sun visibility of a point (terrain/canopy shadows via the shadow-height map): lit iff
  // p.z >= S(cell of p). Always true outside the grid; false when the sun is off.
  bool sunlit(const glm::dvec3& p) const;

  // The motorway centre line at road-surface height (world frame; empty if the road is off).
  const Spline3& road() const { return road_; }
  // The world's named places (landmarks.h), found on first use and kept (thread-safe): the
  // scans take a fraction of a second, and every run of a sweep asks.
  const WorldLandmarks& landmarks() const;
  // The lighting at the start (time 0) when it is not the first model's: what renders of the
  // world alone (a probe, a view) show. Made on first use and kept (thread-safe).
  const LightingState& start_lighting() const;
  double road_width_m() const { return params_.road.width_m; }

  double far_ground_height() const { return min_surface_; }
  const Rgb& far_ground_radiance() const { return far_radiance_; }

  // Fingerprint of every generated array (heights, shadow map, biomes, albedo, radiance, road).
  std::uint64_t content_hash() const;

  // --- cell-level access for the marchers; (ix, iy) must be inside the grid ---
  std::size_t cell_index(int ix, int iy) const {
    return static_cast<std::size_t>(iy) * static_cast<std::size_t>(nx_) + ix;
  }
  float column_top(int ix, int iy) const { return surface_[cell_index(ix, iy)]; }
  const std::vector<float>& surface_columns() const { return surface_; }
  float column_ground(int ix, int iy) const { return ground_[cell_index(ix, iy)]; }
  Biome cell_biome(int ix, int iy) const { return biome_[cell_index(ix, iy)]; }
  const Rgb& cell_albedo(int ix, int iy) const { return albedo_[cell_index(ix, iy)]; }
  float shadow_height(int ix, int iy) const { return shadow_[cell_index(ix, iy)]; }
  // Smooth shading normal from central differences of the ground (canopy follows the ground).
  glm::dvec3 cell_normal(int ix, int iy) const;
  const Rgb& top_radiance(int ix, int iy) const { return top_radiance_[cell_index(ix, iy)]; }
  // Radiance of a column wall at height z. Walls taller than one cell (steeper than 45 deg:
  // cliffs, cuttings, forest edges) are shaded with the axis normal; lower steps belong to a
  // smooth slope and use the cell's smooth normal.
  Rgb wall_radiance(int ix, int iy, ColumnFace face, double z) const;
  // The shading normal of a face: the cell's terrain normal for its top (and for low walls,
  // which belong to the slope), the wall's axis for a wall higher than a cell.
  glm::dvec3 face_normal(int ix, int iy, ColumnFace face) const;
  float far_ground_albedo() const { return far_albedo_; }
  const HeightPyramid& pyramid() const { return pyramid_; }
  float min_surface() const { return min_surface_; }
  float max_surface() const { return max_surface_; }
  // Local (grid) coordinates of a world-frame xy: origin-relative, in metres.
  glm::dvec2 to_local(double x, double y) const { return {x - origin_.x, y - origin_.y}; }

 private:
  World() = default;
  void allocate(const WorldParams& params);
  // Shadow map, radiance, pyramid and extremes from heights, biomes and albedo.
  void finalize();
  void compute_shadow_heights();
  // The cells of an imported level: its heights, water, forest and albedo (no road).
  void build_from_level(const TerrainLevel& level);

  WorldParams params_;
  Lighting lighting_;
  int nx_ = 0, ny_ = 0;
  double cell_ = 1.0;
  glm::dvec2 origin_{0.0};
  std::vector<float> ground_, surface_, shadow_;
  std::vector<Biome> biome_;
  std::vector<Rgb> albedo_, top_radiance_;
  HeightPyramid pyramid_;
  float min_surface_ = 0.0f, max_surface_ = 0.0f;
  float far_albedo_ = kFarGroundAlbedo;
  Rgb far_radiance_{0.0f};
  Spline3 road_;
  struct LandmarkCache;
  std::shared_ptr<LandmarkCache> landmarks_;  // shared_ptr: World stays movable
  struct StartLighting;
  std::shared_ptr<StartLighting> start_lighting_;
};

}  // namespace ambisim
