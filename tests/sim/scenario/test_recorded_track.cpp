// Recorded telemetry: linear interpolation between samples with the segment's slope as the
// velocity, cuts on the exact frame, receivers alive from their first to their last sample,
// strict CSV errors naming the file and the line, and a scenario hash that follows the files.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>

#include <glm/geometric.hpp>

#include "sim/base/input_error.h"
#include "sim/scenario/camera_path.h"
#include "sim/scenario/receivers.h"
#include "sim/scenario/recorded_track.h"
#include "sim/scenario/scenario.h"

using namespace ambisim;
namespace fs = std::filesystem;

namespace {

// Interpolated positions are sums of a few products of small binary fractions here: exact up
// to one rounding of each (1e-15 m at 500 m).
constexpr double kTol = 1e-12;

bool near(const glm::dvec3& a, const glm::dvec3& b) { return glm::length(a - b) <= kTol; }

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

std::string camera_error(const std::string& text) {
  return error_of([&] { parse_camera_csv(text, "flight.csv"); });
}

std::string receiver_error(const std::string& text, int max_live = 10000) {
  return error_of([&] { parse_receiver_csv(text, "cars.csv", max_live); });
}

CameraPath recorded_path(const std::string& csv) {
  CameraPathRecord r;
  r.type = CameraPathRecord::Type::recorded;
  r.recorded = std::make_shared<const RecordedCamera>(parse_camera_csv(csv, "flight.csv"));
  return CameraPath(r, TerrainQueries{});
}

// A scenario file and its CSV in a fresh temporary directory.
struct TempScenario {
  fs::path dir;
  explicit TempScenario(const std::string& name) {
    dir = fs::temp_directory_path() / ("ambisim_test_recorded_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~TempScenario() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream((dir / name).string(), std::ios::binary) << text;
    return (dir / name).string();
  }
};

constexpr const char* kScenarioText = R"({
  "world": {"size_m": [64, 64], "road": {"enabled": false}},
  "camera": {"type": "recorded", "file": "flight.csv"},
  "frames": {"fps": 10, "duration_s": 1},
  "receivers": {"recorded": {"file": "cars.csv", "size_m": 3}}
})";

}  // namespace

TEST_CASE("a recorded track is linear between samples, with the segment's slope as velocity",
          "[recorded]") {
  const RecordedTrack t({0.0, 2.0, 3.0}, {{0, 0, 0}, {10, 0, 4}, {10, 5, 4}});
  auto s = t.at(1.0);
  CHECK(near(s.position, {5, 0, 2}));
  CHECK(near(s.velocity, {5, 0, 2}));
  s = t.at(0.5);
  CHECK(near(s.position, {2.5, 0, 1}));
  // Exactly at a sample: its position bit for bit, the velocity of the segment leaving it.
  s = t.at(2.0);
  CHECK(s.position == glm::dvec3(10, 0, 4));
  CHECK(near(s.velocity, {0, 5, 0}));
  s = t.at(2.5);
  CHECK(near(s.position, {10, 2.5, 4}));
  // At the last sample: there, with the velocity arriving; before and after: held, at rest.
  s = t.at(3.0);
  CHECK(s.position == glm::dvec3(10, 5, 4));
  CHECK(near(s.velocity, {0, 5, 0}));
  CHECK(t.at(7.0).position == glm::dvec3(10, 5, 4));
  CHECK(t.at(7.0).velocity == glm::dvec3(0.0));
  CHECK(t.at(-1.0).position == glm::dvec3(0, 0, 0));
  CHECK(t.at(-1.0).velocity == glm::dvec3(0.0));
  // One sample: standing there for ever.
  const RecordedTrack one({1.0}, {{3, 4, 5}});
  CHECK(one.at(0.0).position == glm::dvec3(3, 4, 5));
  CHECK(one.at(1.0).velocity == glm::dvec3(0.0));
}

TEST_CASE("a recorded camera reads time,x,y,z[,cut] in any column order", "[recorded]") {
  const RecordedCamera c = parse_camera_csv(
      "# exported by a game\n"
      "x, y ,z,time\n"
      "1,2,3,0\n"
      "\n"
      "4,6,3,0.5\r\n",
      "flight.csv");
  REQUIRE(c.track.size() == 2);
  CHECK(c.track.at(0.25).position == glm::dvec3(2.5, 4, 3));
  CHECK(near(c.track.at(0.25).velocity, {6, 8, 0}));
  CHECK(c.source.file == "flight.csv");
}

TEST_CASE(
    "a cut in a recording teleports on the frame at its time, keeping the old motion up "
    "to it",
    "[recorded]") {
  const CameraPath path = recorded_path(
      "time,x,y,z,cut\n"
      "0,0,0,10,0\n"
      "1,10,0,10,0\n"
      "2,20,0,10,0\n"
      "3,500,0,10,1\n"
      "4,510,0,10,0\n");
  // Before the cut the camera goes on at 10 m/s (the segment into a cut is not interpolated).
  CameraState s = path.state(2.5, 2.4);
  CHECK(near(s.position, {25, 0, 10}));
  CHECK(near(s.velocity, {10, 0, 0}));
  CHECK_FALSE(s.cut);
  // The frame at the cut's time is the cut frame, at the new place with the new motion.
  s = path.state(3.0, 2.9);
  CHECK(s.cut);
  CHECK(s.position == glm::dvec3(500, 0, 10));
  CHECK(near(s.velocity, {10, 0, 0}));
  CHECK_FALSE(path.state(3.1, 3.0).cut);
  // A frame after the cut's time (a sparse recording): still the cut frame, interpolated after.
  s = path.state(3.5, 2.9);
  CHECK(s.cut);
  CHECK(near(s.position, {505, 0, 10}));
  // The first frame never cuts (previous time == time).
  CHECK_FALSE(path.state(3.0, 3.0).cut);
  // A cut on the first sample has nothing to cut from.
  const CameraPath first = recorded_path("time,x,y,z,cut\n0,0,0,0,1\n1,1,0,0,0\n");
  CHECK_FALSE(first.state(0.5, 0.0).cut);
  CHECK(near(first.state(0.5, 0.0).position, {0.5, 0, 0}));
  // Two cuts in a row: the one-sample motion between them stands still.
  const CameraPath twice = recorded_path(
      "time,x,y,z,cut\n0,0,0,0,0\n1,10,0,0,0\n2,90,0,0,1\n"
      "3,300,0,0,1\n");
  CHECK(twice.state(2.5, 2.0).position == glm::dvec3(90, 0, 0));
  CHECK(twice.state(2.5, 2.0).velocity == glm::dvec3(0.0));
  CHECK(twice.state(3.0, 2.5).cut);
  CHECK(twice.state(3.0, 2.5).velocity == glm::dvec3(0.0));
}

TEST_CASE("recorded receivers live from their first to their last sample", "[recorded]") {
  ReceiversRecord rec;
  rec.camera_object.enabled = false;
  RecordedReceiversRecord rr;
  rr.size_m = 3.0;
  rr.tracks = std::make_shared<const RecordedReceivers>(
      parse_receiver_csv("id,time,x,y,z\n"
                         "car_a,0.5,0,0,1\n"
                         "car_b,0,100,0,1\n"
                         "car_a,1.0,10,0,1\n"
                         "car_b,2,100,40,1\n"
                         "blink,0.51,7,7,7\n"  // its whole life falls between two frames at 10 fps
                         "blink,0.55,7,7,8\n",
                         "cars.csv", 100));
  CHECK(rr.tracks->ids == std::vector<std::string>{"car_b", "car_a", "blink"});
  rec.recorded = rr;
  ReceiverSet set(rec, TerrainQueries{});
  std::map<int, std::vector<Receiver>> live;
  std::vector<std::pair<double, Receiver>> gone;
  for (int k = 0; k <= 25; ++k) {
    const double t = k / 10.0;
    set.update(t, CameraState{});
    live[k] = set.live();
    for (const auto& g : set.despawned()) gone.push_back({t, g});
  }
  // Frame 0: car_b only (id 1); frame 5 (t = 0.5): car_a appears (id 2) at its first sample.
  REQUIRE(live[0].size() == 1);
  CHECK(live[0][0].id == 1);
  CHECK(live[0][0].kind == ReceiverKind::recorded);
  CHECK(live[0][0].size_m == 3.0);
  REQUIRE(live[5].size() == 2);
  CHECK(live[5][1].id == 2);
  CHECK(live[5][1].spawn_time == 0.5);
  CHECK(live[5][1].position == glm::dvec3(0, 0, 1));
  // Interpolated: car_a at t = 0.7 is 40 % of the way, moving at 20 m/s; car_b at 10 m/s north.
  CHECK(near(live[7][1].position, {4, 0, 1}));
  CHECK(near(live[7][1].velocity, {20, 0, 0}));
  CHECK(near(live[7][0].position, {100, 14, 1}));
  CHECK(near(live[7][0].velocity, {0, 20, 0}));
  // Despawn at the last sample: car_a is live at t = 1.0 (its last sample), gone at t = 1.1.
  REQUIRE(live[10].size() == 2);
  CHECK(live[10][1].position == glm::dvec3(10, 0, 1));
  CHECK(live[11].size() == 1);
  REQUIRE(gone.size() == 2);
  CHECK(gone[0].first == Approx(1.1));
  CHECK(gone[0].second.id == 2);
  CHECK(gone[0].second.despawn_time == gone[0].first);
  // car_b's last sample is at 2.0: live there, gone at 2.1; nothing afterwards.
  CHECK(live[20].size() == 1);
  CHECK(live[20][0].position == glm::dvec3(100, 40, 1));
  CHECK(live[21].empty());
  CHECK(gone[1].first == Approx(2.1));
  CHECK(set.counters().spawned[static_cast<int>(ReceiverKind::recorded)] == 2);
  CHECK(set.counters().despawned[static_cast<int>(ReceiverKind::recorded)] == 2);
  CHECK(set.counters().recorded_missed == 1);
}

TEST_CASE("recorded velocities are used at the samples and interpolated between them",
          "[recorded]") {
  const RecordedCamera c = parse_camera_csv(
      "time,x,y,z,vx,vy,vz,cut\n"
      "0,0,0,0,8,0,0,0\n"
      "1,10,0,0,12,0,0,0\n"
      "2,20,0,0,10,2,0,0\n"
      "3,900,0,0,-4,0,0,1\n",
      "flight.csv");
  // At a sample: as recorded; between: the position linear, the velocity linear too.
  CHECK(c.track.at(1.0).velocity == glm::dvec3(12, 0, 0));
  CHECK(near(c.track.at(0.25).position, {2.5, 0, 0}));
  CHECK(near(c.track.at(0.25).velocity, {9, 0, 0}));
  // Into the cut: on with the velocity recorded at the sample before it.
  CHECK(near(c.track.at(2.5).position, {25, 1, 0}));
  CHECK(near(c.track.at(2.5).velocity, {10, 2, 0}));
  CHECK(c.track.at(3.0).velocity == glm::dvec3(-4, 0, 0));
  CHECK(c.track.at(3.5).velocity == glm::dvec3(0.0));  // held after the last sample
  const RecordedReceivers r = parse_receiver_csv(
      "id,time,x,y,z,vx,vy,vz\nbus,0,0,0,1,3,0,0\nbus,2,10,0,1,7,0,0\n", "cars.csv", 10);
  CHECK(near(r.tracks[0].at(1.0).velocity, {5, 0, 0}));
  CHECK(r.tracks[0].at(2.0).velocity == glm::dvec3(7, 0, 0));
}

TEST_CASE("recordings round-trip through camera_csv bit for bit", "[recorded]") {
  std::vector<CameraSample> samples;
  for (int k = 0; k < 50; ++k) {
    const double t = k / 60.0;
    samples.push_back({t,
                       {2344.0 + 0.1 * t * t, 1e6 / 3.0 + std::sin(t), -1.0 / 7.0},
                       {0.2 * t, std::cos(t), 1.0 / 3.0},
                       k == 30});
  }
  const RecordedCamera c = parse_camera_csv(camera_csv(samples), "rec.csv");
  REQUIRE(c.track.size() == samples.size());
  for (std::size_t k = 0; k < samples.size(); ++k) {
    CHECK(c.track.times()[k] == samples[k].time);
    CHECK(c.track.positions()[k] == samples[k].position);
    CHECK(c.track.at(samples[k].time).position == samples[k].position);
    CHECK(c.track.at(samples[k].time).velocity == samples[k].velocity);
  }
  CHECK(c.track.cut_in(samples[29].time, samples[30].time));
  CHECK_FALSE(c.track.cut_in(samples[30].time, samples[49].time));
}

TEST_CASE("bad recordings are refused naming the file and the line", "[recorded]") {
  CHECK(camera_error("") ==
        "flight.csv: is empty; expected a header line time,x,y,z[,cut][,vx,vy,vz] and "
        "samples");
  CHECK(camera_error("\n# just a comment\n") ==
        "flight.csv: is empty; expected a header line time,x,y,z[,cut][,vx,vy,vz] and samples");
  CHECK(camera_error("time,x,y,z\n") ==
        "flight.csv: line 1: a header and no samples; at least one sample is needed");
  CHECK(camera_error("0,1,2,3\n1,2,3,4\n") ==
        "flight.csv: line 1: expected a header line time,x,y,z[,cut][,vx,vy,vz], got numbers");
  CHECK(camera_error("time,x,y\n0,1,2\n") ==
        "flight.csv: line 1: missing column 'z'; the header needs time, x, y, z (optional: cut, "
        "vx, vy, vz)");
  CHECK(camera_error("time,x,y,z,speed\n0,1,2,3,4\n") ==
        "flight.csv: line 1: unknown column 'speed'; valid columns: time, x, y, z, cut, vx, vy, vz "
        "(a header line is required)");
  CHECK(camera_error("time,x,y,z,x\n0,1,2,3,4\n") ==
        "flight.csv: line 1: column 'x' appears twice");
  CHECK(camera_error("time,x,y,z\n0,1,2,3\n1,1,2,3\n1,1,2,3\n") ==
        "flight.csv: line 4: time 1 is not after the previous sample's 1 (times must increase)");
  CHECK(camera_error("time,x,y,z\n0,1,2,3\n-1,1,2,3\n") ==
        "flight.csv: line 3: time -1 is not after the previous sample's 0 (times must increase)");
  CHECK(camera_error("time,x,y,z\n0,1,2,3\n1,1,abc,3\n") ==
        "flight.csv: line 3: y: not a number: 'abc'");
  CHECK(camera_error("time,x,y,z\n0,1,,3\n") == "flight.csv: line 2: y: empty; expected a number");
  CHECK(camera_error("time,x,y,z\n0,1,nan,3\n") == "flight.csv: line 2: y: not a number: 'nan'");
  CHECK(camera_error("time,x,y,z\n0,1,1e999,3\n") ==
        "flight.csv: line 2: y: '1e999' is out of range");
  CHECK(camera_error("time,x,y,z\n0,1,2\n") ==
        "flight.csv: line 2: has 3 fields, the header has 4");
  CHECK(camera_error("time,x,y,z,cut\n0,1,2,3,2\n") ==
        "flight.csv: line 2: cut: must be 0 or 1, got 2");
  CHECK(camera_error("time,x,y,z\n0,1,2e11,3\n") ==
        "flight.csv: line 2: y: must be within +-1e+10 m, got 2e+11");
  CHECK(camera_error("time,x,y,z,vx,vz\n0,1,2,3,4,5\n") ==
        "flight.csv: line 1: missing column 'vy'; a velocity needs all of vx, vy, vz");
  CHECK(camera_error("time,x,y,z,vx,vy,vz\n0,1,2,3,4,5e7,6\n") ==
        "flight.csv: line 2: vy: must be within +-1000000 m/s, got 50000000");
  CHECK(camera_error("time,x,y,z\n1e12,1,2,3\n") ==
        "flight.csv: line 2: time: must be within +-1e9 s, got 1e+12");
  // A repeated header line is not skipped: it is a row that is not numbers.
  CHECK(camera_error("time,x,y,z\n0,1,2,3\ntime,x,y,z\n") ==
        "flight.csv: line 3: time: not a number: 'time'");

  CHECK(receiver_error("id,time,x,y\na,0,1,2\n") ==
        "cars.csv: line 1: missing column 'z'; the header needs id, time, x, y, z (optional: vx, "
        "vy, vz)");
  CHECK(receiver_error("id,time,x,y,z,cut\na,0,1,2,3,0\n") ==
        "cars.csv: line 1: unknown column 'cut'; valid columns: id, time, x, y, z, vx, vy, vz (a "
        "header line is required)");
  CHECK(receiver_error("id,time,x,y,z\na,0,1,2,3\nb,0,1,2,3\na,0,1,2,3\n") ==
        "cars.csv: line 4: time 0 is not after the previous sample's 0 of id a (times must "
        "increase)");
  CHECK(receiver_error("id,time,x,y,z\n ,0,1,2,3\n") == "cars.csv: line 2: id: empty");
  CHECK(receiver_error("id,time,x,y,z\na,0,1,2,3\nb,1,1,2,3\nc,1,1,2,3\na,1,1,2,3\n", 2) ==
        "cars.csv: 3 receivers alive at once at time 1 s; at most 2");
}

TEST_CASE("a scenario reads its recordings relative to its file and hashes their contents",
          "[recorded]") {
  const TempScenario tmp("hash");
  const std::string scenario = tmp.write("scene.json", kScenarioText);
  tmp.write("flight.csv", "time,x,y,z\n0,10,10,5\n1,20,10,5\n");
  tmp.write("cars.csv", "id,time,x,y,z\n1,0,12,10,1\n1,1,22,10,1\n");
  const Scenario a = load_scenario(scenario);
  REQUIRE(a.camera.type == CameraPathRecord::Type::recorded);
  REQUIRE(a.camera.recorded);
  CHECK(a.camera.recorded->track.size() == 2);
  REQUIRE(a.receivers.recorded);
  CHECK(a.receivers.recorded->size_m == 3.0);
  CHECK(a.receivers.recorded->tracks->tracks.size() == 1);
  // Same files, same hash; a changed sample changes both hashes though the JSON did not change.
  CHECK(load_scenario(scenario).hash() == a.hash());
  tmp.write("flight.csv", "time,x,y,z\n0,10,10,5\n1,20,10,6\n");
  const Scenario b = load_scenario(scenario);
  CHECK(b.document == a.document);
  CHECK(b.hash() != a.hash());
  CHECK(b.reference_hash() != a.reference_hash());
  tmp.write("cars.csv", "id,time,x,y,z\n1,0,12,10,1\n1,1,22,10,2\n");
  const Scenario c = load_scenario(scenario);
  CHECK(c.hash() != b.hash());
  CHECK(c.reference_hash() != b.reference_hash());
  // A scenario without recordings keeps the hash of its document alone.
  nlohmann::json plain = nlohmann::json::parse(kScenarioText);
  plain["camera"] = {{"points", {{0, 0, 5}, {50, 0, 5}}}, {"speed_mps", 5}};
  plain.erase("receivers");
  const Scenario p1 = parse_scenario(plain, scenario);
  plain["camera"]["speed_mps"] = 6;
  CHECK(parse_scenario(plain, scenario).hash() != p1.hash());
}

TEST_CASE("recorded sections are read strictly", "[recorded]") {
  const TempScenario tmp("strict");
  tmp.write("flight.csv", "time,x,y,z\n0,10,10,5\n1,20,10,5\n");
  tmp.write("cars.csv", "id,time,x,y,z\n1,0,12,10,1\n");
  const std::string file = (tmp.dir / "scene.json").string();
  auto parse_error = [&](const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json d = nlohmann::json::parse(kScenarioText);
    edit(d);
    return error_of([&] { parse_scenario(d, file); });
  };
  CHECK_THAT(parse_error([](nlohmann::json& d) { d["camera"]["speed_mps"] = 3; }),
             Catch::Contains("/camera/speed_mps: unknown key; valid keys: file, type, view"));
  CHECK_THAT(parse_error([](nlohmann::json& d) { d["camera"].erase("file"); }),
             Catch::Contains("/camera/file: required string is missing"));
  CHECK_THAT(parse_error([](nlohmann::json& d) { d["camera"]["file"] = "nope.csv"; }),
             Catch::Contains("scene.json: /camera/file: no such file: "));
  CHECK_THAT(parse_error([](nlohmann::json& d) { d["camera"]["file"] = "."; }),
             Catch::Contains("/camera/file: is a directory"));
  CHECK_THAT(parse_error([](nlohmann::json& d) { d["receivers"]["recorded"]["size_m"] = 0; }),
             Catch::Contains("/receivers/recorded/size_m: must be > 0"));
  CHECK_THAT(parse_error([](nlohmann::json& d) { d["receivers"]["recorded"]["speed"] = 0; }),
             Catch::Contains("/receivers/recorded/speed: unknown key"));
  tmp.write("bad.csv", "time,x,y,z\n0,1,2,3\n0,1,2,3\n");
  CHECK_THAT(parse_error([](nlohmann::json& d) { d["camera"]["file"] = "bad.csv"; }),
             Catch::Contains("bad.csv: line 3: time 0 is not after"));
}
