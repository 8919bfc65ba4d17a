#include "sim/scenario/landmark_ref.h"

#include <cmath>

#include "sim/base/input_error.h"
#include "sim/world/landmarks.h"

namespace ambisim {
namespace {

std::string valid_names() {
  std::string s;
  for (const auto& n : landmark_names()) s += (s.empty() ? "" : ", ") + n;
  return s;
}

glm::dvec3 read_coordinates(const nlohmann::json& p, const std::string& file,
                            const std::string& path, double max_coord) {
  if (!p.is_array() || p.size() != 3) {
    throw InputError(file, path, "must be [x, y, z] or {\"landmark\": NAME, \"offset\": [...]}");
  }
  glm::dvec3 q;
  for (int c = 0; c < 3; ++c) {
    const std::string at = path + "/" + std::to_string(c);
    if (!p[c].is_number() || !std::isfinite(p[c].get<double>())) {
      throw InputError(file, at, "must be a finite number");
    }
    q[c] = p[c].get<double>();
    if (std::abs(q[c]) > max_coord) {
      // Bounds are powers of ten: written 1e10, as in the schema.
      const std::string m =
          "1e" + std::to_string(static_cast<int>(std::lround(std::log10(max_coord))));
      throw InputError(file, at, "must be in [-" + m + ", " + m + "] m, got " + p[c].dump());
    }
  }
  return q;
}

}  // namespace

glm::dvec3 read_position(const nlohmann::json& v, const std::string& file, const std::string& path,
                         double max_coord, std::vector<LandmarkRef>& refs, std::size_t index) {
  if (!v.is_object()) return read_coordinates(v, file, path, max_coord);
  ObjectReader o(v, file, path);
  LandmarkRef ref;
  ref.index = index;
  ref.path = path;
  ref.name = o.string("landmark");
  if (!is_landmark_name(ref.name)) {
    o.fail("landmark", "unknown landmark \"" + ref.name + "\"; valid landmarks: " + valid_names());
  }
  ref.offset = o.vec3("offset", glm::dvec3(0.0), Range::closed(-1e5, 1e5));
  o.finish();
  refs.push_back(std::move(ref));
  return glm::dvec3(0.0);
}

glm::dvec3 read_position(ObjectReader& r, std::string_view key, double max_coord,
                         std::vector<LandmarkRef>& refs, std::size_t index) {
  const nlohmann::json* v = r.raw(key);
  if (v == nullptr) r.fail(key, "required position is missing");
  return read_position(*v, r.file(), r.path_of(key), max_coord, refs, index);
}

glm::dvec3 resolve_landmark(const LandmarkRef& ref, const WorldLandmarks& landmarks,
                            const std::string& file) {
  const auto frame = landmark_frame(landmarks, ref.name);
  if (!frame) {
    throw InputError(file, ref.path + "/landmark",
                     "this world (its seed and settings) has no " + ref.name);
  }
  glm::dvec3 p = frame->point(ref.offset);
  if (ref.z_is_height) p.z = ref.offset.z;
  return p;
}

void resolve_landmarks(const std::vector<LandmarkRef>& refs, const WorldLandmarks& landmarks,
                       const std::string& file, std::vector<glm::dvec3>& positions) {
  for (const auto& ref : refs) positions.at(ref.index) = resolve_landmark(ref, landmarks, file);
}

}  // namespace ambisim
