#pragma once
// Scenario positions that name a landmark of the world instead of coordinates, so one scenario
// runs on any world seed (SPEC section 5, "Seeds and statistics").
//
// JSON: wherever a position [x, y, z] is read (camera keyframes, a cut's to_position, the LOD
// trigger, the view's look_at), {"landmark": NAME, "offset": [along, left, up]} may stand
// instead: the landmark's origin (z = the ground there) plus `offset` in its frame
// (landmarks.h: along = toward the forest, along the road, over the cliff; left = along turned
// counter-clockwise; up = +z); `offset` defaults to [0, 0, 0]. With keyframes in
// z_mode "above_ground", `up` is the height above the ground, as z is for coordinates.
//
// An unknown NAME is an input error when the file is read (listing the valid names); a landmark
// the world does not have (no road, no forest edge) is an input error when the world is built,
// before anything runs (check_scenario_world).
#include <cstddef>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "sim/base/json_reader.h"

namespace ambisim {

struct WorldLandmarks;

struct LandmarkRef {
  std::size_t index = 0;  // which position of its list it fills
  std::string name;
  glm::dvec3 offset{0.0};
  bool z_is_height = false;  // up is a height above the ground (keyframes, above_ground)
  std::string path;          // JSON path, for errors once the world is known
};

// The bound on every scenario coordinate: the world's origin may lie up to 1e9 m away, so 1e10 m
// bounds every real coordinate while keeping differences and lengths finite.
inline constexpr double kMaxScenarioCoord = 1e10;  // m

// Reads the position at `key` of `r`: coordinates (each within +-max_coord) are returned as is;
// a landmark object is appended to `refs` (with `index`) and (0, 0, 0) returned, to be filled in
// by resolve_landmarks.
glm::dvec3 read_position(ObjectReader& r, std::string_view key, double max_coord,
                         std::vector<LandmarkRef>& refs, std::size_t index);
// The same for a JSON value at `path` (array elements).
glm::dvec3 read_position(const nlohmann::json& v, const std::string& file, const std::string& path,
                         double max_coord, std::vector<LandmarkRef>& refs, std::size_t index);

// Writes each ref's position into positions[ref.index]; throws InputError(file, ref.path) when
// the world has no such landmark.
void resolve_landmarks(const std::vector<LandmarkRef>& refs, const WorldLandmarks& landmarks,
                       const std::string& file, std::vector<glm::dvec3>& positions);
glm::dvec3 resolve_landmark(const LandmarkRef& ref, const WorldLandmarks& landmarks,
                            const std::string& file);

}  // namespace ambisim
