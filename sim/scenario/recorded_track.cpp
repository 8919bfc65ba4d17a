#include "sim/scenario/recorded_track.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "sim/base/csv_table.h"
#include "sim/base/hash.h"
#include "sim/base/input_error.h"
#include "sim/scenario/landmark_ref.h"

namespace ambisim {
namespace {

constexpr double kMaxTime = 1e9;   // s
constexpr double kMaxSpeed = 1e6;  // m/s, each velocity component

std::string number_text(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

std::string short_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", x);
  return buf;
}

// `expected` spells the header for messages ("time,x,y,z[,cut][,vx,vy,vz]").
CsvTable parse_table(std::string_view text, const std::string& file,
                     const std::vector<std::string>& required,
                     const std::vector<std::string>& optional, const std::string& expected) {
  // Nothing but blanks and '#' comments: no header.
  bool empty = true;
  for (std::size_t pos = 0; empty && pos < text.size();) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    const std::string_view line = text.substr(pos, end - pos);
    const std::size_t first = line.find_first_not_of(" \t\r");
    empty = first == std::string_view::npos || line[0] == '#';
    pos = end + 1;
  }
  if (empty) {
    throw InputError(file, "", "is empty; expected a header line " + expected + " and samples");
  }
  // Repeated header lines are rows like any other here (and not numbers).
  const CsvTable t = parse_csv(text, file, false);
  // A first line of numbers is data without a header.
  bool all_numbers = true;
  for (const auto& h : t.header) {
    double v = 0.0;
    all_numbers = all_numbers && !h.empty() && std::sscanf(h.c_str(), "%lf", &v) == 1;
  }
  if (all_numbers) {
    throw InputError(file, "line " + std::to_string(t.header_line),
                     "expected a header line " + expected + ", got numbers");
  }
  t.check_columns(required, optional);
  if (t.rows.empty()) {
    throw InputError(file, "line " + std::to_string(t.header_line),
                     "a header and no samples; at least one sample is needed");
  }
  return t;
}

double read_time(const CsvTable& t, std::size_t row, int col) {
  const double v = t.finite_number(row, col);
  if (v < -kMaxTime || v > kMaxTime) {
    throw InputError(t.file, t.where(row), "time: must be within +-1e9 s, got " + short_number(v));
  }
  return v;
}

// Three columns as a vector, each within +-limit (`unit` names it in messages).
glm::dvec3 read_vector(const CsvTable& t, std::size_t row, const int (&cols)[3], double limit,
                       const char* unit) {
  glm::dvec3 p;
  for (int a = 0; a < 3; ++a) {
    p[a] = t.finite_number(row, cols[a]);
    if (p[a] < -limit || p[a] > limit) {
      throw InputError(t.file, t.where(row),
                       t.header[static_cast<std::size_t>(cols[a])] + ": must be within +-" +
                           short_number(limit) + " " + unit + ", got " + short_number(p[a]));
    }
  }
  return p;
}

// The columns of x, y, z and, if the header has them, of vx, vy, vz (all three or none).
struct VectorColumns {
  int position[3] = {-1, -1, -1};
  int velocity[3] = {-1, -1, -1};
  bool has_velocity = false;
};

VectorColumns vector_columns(const CsvTable& t) {
  VectorColumns c;
  int given = 0;
  for (int a = 0; a < 3; ++a) {
    c.position[a] = t.column(std::string(1, static_cast<char>('x' + a)));
    c.velocity[a] = t.column(kVelocityCsvColumns[static_cast<std::size_t>(a)]);
    given += c.velocity[a] >= 0 ? 1 : 0;
  }
  if (given != 0 && given != 3) {
    for (int a = 0; a < 3; ++a) {
      if (c.velocity[a] < 0) {
        throw InputError(t.file, "line " + std::to_string(t.header_line),
                         "missing column '" + kVelocityCsvColumns[static_cast<std::size_t>(a)] +
                             "'; a velocity needs all of vx, vy, vz");
      }
    }
  }
  c.has_velocity = given == 3;
  return c;
}

void check_increasing(const CsvTable& t, std::size_t row, double previous, double time,
                      const std::string& what) {
  if (!(time > previous)) {
    throw InputError(t.file, t.where(row),
                     "time " + short_number(time) + " is not after the previous sample's " +
                         short_number(previous) + what + " (times must increase)");
  }
}

struct FileBytes {
  std::string path;
  std::string bytes;
};

FileBytes read_named_file(ObjectReader& r, std::string_view key) {
  namespace fs = std::filesystem;
  const std::string name = r.string(key);
  if (name.empty()) r.fail(key, "must name a CSV file");
  const fs::path base = fs::path(r.file()).parent_path();
  const std::string path = (base / name).lexically_normal().string();
  std::error_code ec;
  const auto status = fs::status(path, ec);
  if (ec || !fs::exists(status)) r.fail(key, "no such file: " + path);
  if (fs::is_directory(status)) r.fail(key, "is a directory, not a CSV file: " + path);
  std::ifstream in(path, std::ios::binary);
  if (!in) r.fail(key, "cannot be opened for reading: " + path);
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) r.fail(key, "read error: " + path);
  return {path, buffer.str()};
}

std::uint64_t bytes_hash(std::string_view bytes) {
  ContentHasher h;
  h.add_bytes(bytes.data(), bytes.size());
  return h.value();
}

}  // namespace

RecordedTrack::RecordedTrack(std::vector<double> times, std::vector<glm::dvec3> positions,
                             std::vector<bool> cuts, std::vector<glm::dvec3> velocities)
    : times_(std::move(times)),
      positions_(std::move(positions)),
      cuts_(std::move(cuts)),
      velocities_(std::move(velocities)) {
  if (times_.empty() || times_.size() != positions_.size()) {
    throw std::invalid_argument("a recorded track needs one position per sample, at least one");
  }
  if (cuts_.empty()) cuts_.assign(times_.size(), false);
  if (cuts_.size() != times_.size()) throw std::invalid_argument("one cut flag per sample");
  if (!velocities_.empty() && velocities_.size() != times_.size()) {
    throw std::invalid_argument("one velocity per sample, or none");
  }
  const std::size_t n = times_.size();
  segment_velocity_.assign(n > 1 ? n - 1 : 0, glm::dvec3(0.0));
  segment_moves_.assign(n > 1 ? n - 1 : 0, false);
  for (std::size_t k = 0; k + 1 < n; ++k) {
    if (!(times_[k + 1] > times_[k])) throw std::invalid_argument("times must increase");
    segment_moves_[k] = !cuts_[k + 1];
    if (segment_moves_[k]) {
      segment_velocity_[k] = (positions_[k + 1] - positions_[k]) / (times_[k + 1] - times_[k]);
    }
  }
  // A segment that ends in a cut continues the motion before it (if sample k began no new
  // motion of its own): the camera keeps going until it is teleported.
  for (std::size_t k = 1; k + 1 < n; ++k) {
    if (!segment_moves_[k] && !cuts_[k]) segment_velocity_[k] = segment_velocity_[k - 1];
  }
  // With recorded velocities, the one at sample k carries a segment that ends in a cut.
  if (!velocities_.empty()) {
    for (std::size_t k = 0; k + 1 < n; ++k) {
      if (!segment_moves_[k]) segment_velocity_[k] = velocities_[k];
    }
  }
}

RecordedTrack::State RecordedTrack::at(double time) const {
  const std::size_t n = times_.size();
  if (time < times_.front() || time > times_.back()) {
    return {time < times_.front() ? positions_.front() : positions_.back(), glm::dvec3(0.0)};
  }
  const bool recorded = !velocities_.empty();
  if (n == 1) return {positions_.front(), recorded ? velocities_.front() : glm::dvec3(0.0)};
  const auto it = std::upper_bound(times_.begin(), times_.end(), time);
  const std::size_t k = static_cast<std::size_t>(it - times_.begin()) - 1;
  if (k == n - 1) {
    // At the last sample: the velocity arriving there (none after a cut onto it).
    if (recorded) return {positions_.back(), velocities_.back()};
    return {positions_.back(), cuts_.back() ? glm::dvec3(0.0) : segment_velocity_[n - 2]};
  }
  if (time == times_[k]) {
    return {positions_[k], recorded ? velocities_[k] : segment_velocity_[k]};
  }
  const double f = (time - times_[k]) / (times_[k + 1] - times_[k]);
  if (segment_moves_[k]) {
    const glm::dvec3 v = recorded ? velocities_[k] + (velocities_[k + 1] - velocities_[k]) * f
                                  : segment_velocity_[k];
    return {positions_[k] + (positions_[k + 1] - positions_[k]) * f, v};
  }
  return {positions_[k] + segment_velocity_[k] * (time - times_[k]), segment_velocity_[k]};
}

bool RecordedTrack::cut_in(double t0, double t1) const {
  auto it = std::upper_bound(times_.begin(), times_.end(), t0);
  for (; it != times_.end() && *it <= t1; ++it) {
    const std::size_t k = static_cast<std::size_t>(it - times_.begin());
    if (k > 0 && cuts_[k]) return true;
  }
  return false;
}

RecordedCamera parse_camera_csv(std::string_view text, const std::string& file) {
  const CsvTable t = parse_table(text, file, kCameraCsvColumns, {"cut", "vx", "vy", "vz"},
                                 "time,x,y,z[,cut][,vx,vy,vz]");
  const int ct = t.column("time"), cc = t.column("cut");
  const VectorColumns vc = vector_columns(t);
  std::vector<double> times;
  std::vector<glm::dvec3> positions, velocities;
  std::vector<bool> cuts;
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const double time = read_time(t, i, ct);
    if (!times.empty()) check_increasing(t, i, times.back(), time, "");
    times.push_back(time);
    positions.push_back(read_vector(t, i, vc.position, kMaxScenarioCoord, "m"));
    if (vc.has_velocity) velocities.push_back(read_vector(t, i, vc.velocity, kMaxSpeed, "m/s"));
    bool cut = false;
    if (cc >= 0) {
      const double c = t.finite_number(i, cc);
      if (c != 0.0 && c != 1.0) {
        throw InputError(file, t.where(i), "cut: must be 0 or 1, got " + short_number(c));
      }
      cut = c == 1.0;
    }
    cuts.push_back(cut);
  }
  RecordedCamera out;
  out.source.file = file;
  out.source.content_hash = bytes_hash(text);
  out.track =
      RecordedTrack(std::move(times), std::move(positions), std::move(cuts), std::move(velocities));
  return out;
}

RecordedReceivers parse_receiver_csv(std::string_view text, const std::string& file, int max_live) {
  const CsvTable t =
      parse_table(text, file, kReceiverCsvColumns, kVelocityCsvColumns, "id,time,x,y,z[,vx,vy,vz]");
  const int cid = t.column("id"), ct = t.column("time");
  const VectorColumns vc = vector_columns(t);
  struct Building {
    std::size_t first_row = 0;
    std::vector<double> times;
    std::vector<glm::dvec3> positions, velocities;
  };
  std::map<std::string, std::size_t> index;
  std::vector<std::string> ids;
  std::vector<Building> tracks;
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const std::string id(t.text(i, cid));
    const std::size_t a = id.find_first_not_of(" \t");
    if (a == std::string::npos) throw InputError(file, t.where(i), "id: empty");
    const std::string key = id.substr(a, id.find_last_not_of(" \t") - a + 1);
    const auto [it, added] = index.try_emplace(key, tracks.size());
    if (added) {
      ids.push_back(key);
      tracks.push_back({i, {}, {}, {}});
    }
    Building& b = tracks[it->second];
    const double time = read_time(t, i, ct);
    if (!b.times.empty()) check_increasing(t, i, b.times.back(), time, " of id " + key);
    b.times.push_back(time);
    b.positions.push_back(read_vector(t, i, vc.position, kMaxScenarioCoord, "m"));
    if (vc.has_velocity) b.velocities.push_back(read_vector(t, i, vc.velocity, kMaxSpeed, "m/s"));
  }
  // Spawn order: by first sample time, then by the first row in the file.
  std::vector<std::size_t> order(tracks.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return tracks[a].times.front() < tracks[b].times.front();
  });
  // At most max_live alive at once (both ends included: starts count before ends at a tie).
  std::vector<std::pair<double, int>> events;
  for (const auto& b : tracks) {
    events.push_back({b.times.front(), 0});
    events.push_back({b.times.back(), 1});
  }
  std::sort(events.begin(), events.end());
  int alive = 0;
  for (const auto& [time, end] : events) {
    alive += end ? -1 : 1;
    if (alive > max_live) {
      throw InputError(file, "",
                       std::to_string(alive) + " receivers alive at once at time " +
                           short_number(time) + " s; at most " + std::to_string(max_live));
    }
  }
  RecordedReceivers out;
  out.source.file = file;
  out.source.content_hash = bytes_hash(text);
  for (std::size_t k : order) {
    out.ids.push_back(ids[k]);
    out.tracks.emplace_back(std::move(tracks[k].times), std::move(tracks[k].positions),
                            std::vector<bool>(), std::move(tracks[k].velocities));
  }
  return out;
}

std::shared_ptr<const RecordedCamera> read_recorded_camera(ObjectReader& r, std::string_view key) {
  const FileBytes f = read_named_file(r, key);
  return std::make_shared<const RecordedCamera>(parse_camera_csv(f.bytes, f.path));
}

std::shared_ptr<const RecordedReceivers> read_recorded_receivers(ObjectReader& r,
                                                                 std::string_view key,
                                                                 int max_live) {
  const FileBytes f = read_named_file(r, key);
  return std::make_shared<const RecordedReceivers>(parse_receiver_csv(f.bytes, f.path, max_live));
}

std::string camera_csv(const std::vector<CameraSample>& samples) {
  std::string out = "time,x,y,z,vx,vy,vz,cut\n";
  for (const auto& s : samples) {
    out += number_text(s.time);
    for (int a = 0; a < 3; ++a) out += "," + number_text(s.position[a]);
    for (int a = 0; a < 3; ++a) out += "," + number_text(s.velocity[a]);
    out += s.cut ? ",1\n" : ",0\n";
  }
  return out;
}

}  // namespace ambisim
