#include "sim/scenario/scenario.h"

#include <cstdio>
#include <filesystem>

#include "sim/base/hash.h"
#include "sim/base/json_reader.h"
#include "sim/world/world.h"

namespace ambisim {
namespace {

// Bumped whenever the meaning of a scenario field changes, so old hashes stop matching.
constexpr std::uint64_t kScenarioFormat = 1;

std::uint64_t hash_json(const nlohmann::json& j) {
  // nlohmann::json keeps object keys sorted, so dump() is canonical for equal documents.
  const std::string text = j.dump();
  ContentHasher h;
  h.add_value(kScenarioFormat);
  h.add_bytes(text.data(), text.size());
  return h.value();
}

// The recordings a scenario reads (CSV files): their contents are part of its fingerprint, so a
// changed file changes the hash even though the document naming it did not change.
std::uint64_t with_recordings(std::uint64_t h, const Scenario& s) {
  // An imported level's images likewise (their decoded contents).
  if (s.world.level) h = hash_combine(h, s.world.level->content_hash);
  if (s.camera.recorded) h = hash_combine(h, s.camera.recorded->source.content_hash);
  if (s.receivers.recorded && s.receivers.recorded->tracks) {
    h = hash_combine(h, s.receivers.recorded->tracks->source.content_hash);
  }
  return h;
}

ReferenceSettings parse_reference(ObjectReader& r) {
  ReferenceSettings s;
  s.face_size = r.integer("face_size", s.face_size, Range::closed(4, 256));
  s.interval_s = r.number("interval_s", s.interval_s, Range::closed(0.0, 10.0));
  s.refine_de = r.number("refine_de", s.refine_de, Range::positive());
  s.sample_stride = r.integer("sample_stride", s.sample_stride, Range::closed(1, 1e6));
  s.sample_seed = static_cast<std::uint64_t>(r.integer("sample_seed", 1, Range::closed(0, 2e9)));
  r.finish();
  return s;
}

}  // namespace

std::string hex64(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

std::uint64_t Scenario::hash() const { return with_recordings(hash_json(document), *this); }

std::uint64_t Scenario::reference_hash() const {
  nlohmann::json d = document;
  d.erase("budget");
  d.erase("name");
  d.erase("description");
  return with_recordings(hash_json(d), *this);
}

Scenario parse_scenario(const nlohmann::json& document, const std::string& file) {
  Scenario s;
  s.metrics = MetricSettings::defaults();
  s.file = file;
  s.document = document;
  ObjectReader root(document, file, "");
  s.name = root.string("name", std::filesystem::path(file).stem().string());
  s.description = root.string("description", "");
  {
    auto r = root.object("world");
    s.world = parse_world_params(r);
    r.finish();
  }
  {
    auto r = root.object("camera");
    s.camera = parse_camera_path(r);
    r.finish();
  }
  {
    auto r = root.object("frames");
    s.frames = parse_frame_schedule(r);
    r.finish();
  }
  if (auto r = root.optional_object("budget")) {
    s.budget = parse_capture_budget(*r);
    r->finish();
  }
  if (auto r = root.optional_object("receivers")) {
    s.receivers = parse_receivers(*r);
    r->finish();
  }
  if (auto r = root.optional_object("metrics")) {
    s.metrics = parse_metric_settings(*r);
    r->finish();
  }
  if (auto r = root.optional_object("reference")) s.reference = parse_reference(*r);
  root.finish();
  // Sections that depend on each other.
  if (!s.world.road.enabled) {
    const std::string why = s.world.level ? "an imported level (/world/level) has no road"
                                          : "/world/road/enabled is false";
    if (s.camera.type == CameraPathRecord::Type::road) {
      throw InputError(file, "/camera/type", "\"road\" needs the world's road (" + why + ")");
    }
    if (s.receivers.traffic) {
      throw InputError(file, "/receivers/traffic", "needs the world's road (" + why + ")");
    }
  }
  return s;
}

CameraPathRecord resolved_camera(const Scenario& s, const World& world) {
  CameraPathRecord c = s.camera;
  if (!c.point_landmarks.empty() || !c.cut_landmarks.empty() || !c.look_at_landmark.empty()) {
    resolve_camera_landmarks(c, world.landmarks(), s.file);
  }
  return c;
}

ReceiversRecord resolved_receivers(const Scenario& s, const World& world) {
  ReceiversRecord r = s.receivers;
  if (r.lod_props && !r.lod_props->trigger_landmark.empty()) {
    resolve_receiver_landmarks(r, world.landmarks(), s.file);
  }
  return r;
}

void check_scenario_world(const Scenario& s, const World& world) {
  resolved_camera(s, world);
  resolved_receivers(s, world);
  if (s.camera.type == CameraPathRecord::Type::road &&
      s.camera.start_arc_length_m > world.road().length()) {
    char text[96];
    std::snprintf(text, sizeof text, "is beyond the end of the road (%.1f m long), got %.1f",
                  world.road().length(), s.camera.start_arc_length_m);
    throw InputError(s.file, "/camera/start_arc_length_m", text);
  }
}

Scenario load_scenario(const std::string& path) {
  return parse_scenario(load_json_file(path), path);
}

void set_json_path(nlohmann::json& document, const std::string& pointer,
                   const nlohmann::json& value, const std::string& file) {
  if (pointer.empty() || pointer[0] != '/') {
    throw InputError(file, pointer, "a parameter path must start with '/'");
  }
  nlohmann::json* node = &document;
  std::size_t pos = 1;
  while (true) {
    const std::size_t next = pointer.find('/', pos);
    const std::string key = pointer.substr(pos, next == std::string::npos ? next : next - pos);
    if (!node->is_object()) {
      throw InputError(file, pointer.substr(0, pos - 1), "is not an object; cannot set " + pointer);
    }
    if (next == std::string::npos) {
      (*node)[key] = value;
      return;
    }
    node = &(*node)[key];
    if (node->is_null()) *node = nlohmann::json::object();
    pos = next + 1;
  }
}

}  // namespace ambisim
