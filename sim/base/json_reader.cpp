#include "sim/base/json_reader.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace ambisim {
namespace {

// RFC 6901 escaping of one reference token.
std::string escape_token(std::string_view key) {
  std::string out;
  for (char c : key) {
    if (c == '~') {
      out += "~0";
    } else if (c == '/') {
      out += "~1";
    } else {
      out += c;
    }
  }
  return out;
}

std::string type_name(const nlohmann::json& v) { return v.type_name(); }

std::string short_value(const nlohmann::json& v) {
  std::string s = v.dump();
  if (s.size() > 40) s = s.substr(0, 37) + "...";
  return s;
}

std::string format_number(double x) {
  std::ostringstream os;
  os.precision(12);
  os << x;
  return os.str();
}

}  // namespace

nlohmann::json load_json_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const auto status = fs::status(path, ec);
  if (ec || !fs::exists(status)) throw InputError(path, "", "no such file");
  if (fs::is_directory(status)) throw InputError(path, "", "is a directory, not a JSON file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot be opened for reading");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw InputError(path, "", "read error");
  const std::string text = buffer.str();
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) {
    throw InputError(path, "", "is empty; expected a JSON object");
  }
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // Report line and column rather than nlohmann's byte offset.
    const std::size_t at = std::min<std::size_t>(e.byte > 0 ? e.byte - 1 : 0, text.size());
    std::size_t line = 1, col = 1;
    for (std::size_t i = 0; i < at; ++i) {
      if (text[i] == '\n') {
        ++line;
        col = 1;
      } else {
        ++col;
      }
    }
    throw InputError(
        path, "",
        "invalid JSON at line " + std::to_string(line) + ", column " + std::to_string(col));
  } catch (const nlohmann::json::exception& e) {
    // E.g. a number too large for a double (1e999): nlohmann reports it as out_of_range.
    std::string what = e.what();
    const std::size_t close = what.find("] ");
    if (close != std::string::npos) what.erase(0, close + 2);
    throw InputError(path, "", "invalid JSON: " + what);
  }
}

ObjectReader::ObjectReader(const nlohmann::json& j, std::string file, std::string pointer)
    : j_(&j), file_(std::move(file)), pointer_(std::move(pointer)) {
  if (!j.is_object()) {
    throw InputError(file_, pointer_.empty() ? "/" : pointer_,
                     "must be an object, got " + type_name(j));
  }
}

std::string ObjectReader::path_of(std::string_view key) const {
  return pointer_ + "/" + escape_token(key);
}

void ObjectReader::fail(std::string_view key, const std::string& message) const {
  throw InputError(file_, path_of(key), message);
}

bool ObjectReader::has(std::string_view key) const {
  return j_->find(std::string(key)) != j_->end();
}

const nlohmann::json* ObjectReader::find(std::string_view key) {
  known_.emplace(key);
  auto it = j_->find(std::string(key));
  if (it == j_->end()) return nullptr;
  consumed_.emplace(key);
  return &*it;
}

double ObjectReader::checked_number(const nlohmann::json& v, const std::string& path,
                                    Range range) const {
  if (!v.is_number()) {
    throw InputError(file_, path, "must be a number, got " + type_name(v) + " " + short_value(v));
  }
  const double x = v.get<double>();
  if (!std::isfinite(x)) throw InputError(file_, path, "must be finite");
  const bool low = range.min_exclusive ? !(x > range.min) : !(x >= range.min);
  const bool high = range.max_exclusive ? !(x < range.max) : !(x <= range.max);
  if (low) {
    throw InputError(file_, path,
                     std::string("must be ") + (range.min_exclusive ? "> " : ">= ") +
                         format_number(range.min) + ", got " + format_number(x));
  }
  if (high) {
    throw InputError(file_, path,
                     std::string("must be ") + (range.max_exclusive ? "< " : "<= ") +
                         format_number(range.max) + ", got " + format_number(x));
  }
  return x;
}

double ObjectReader::number(std::string_view key, double fallback, Range range) {
  const auto* v = find(key);
  return v ? checked_number(*v, path_of(key), range) : fallback;
}

double ObjectReader::number(std::string_view key, Range range) {
  const auto* v = find(key);
  if (!v) fail(key, "required number is missing");
  return checked_number(*v, path_of(key), range);
}

int ObjectReader::integer(std::string_view key, int fallback, Range range) {
  if (!has(key)) {
    known_.emplace(key);
    return fallback;
  }
  return integer(key, range);
}

int ObjectReader::integer(std::string_view key, Range range) {
  const auto* v = find(key);
  if (!v) fail(key, "required integer is missing");
  if (!v->is_number_integer()) {
    fail(key, "must be an integer, got " + type_name(*v) + " " + short_value(*v));
  }
  const double x = checked_number(*v, path_of(key), range);
  if (x < -2147483648.0 || x > 2147483647.0) fail(key, "integer out of range");
  return static_cast<int>(x);
}

std::uint64_t ObjectReader::seed(std::string_view key, std::uint64_t fallback) {
  const auto* v = find(key);
  if (!v) return fallback;
  if (!v->is_number_unsigned() && !(v->is_number_integer() && v->get<std::int64_t>() >= 0)) {
    fail(key, "must be a non-negative integer, got " + short_value(*v));
  }
  return v->get<std::uint64_t>();
}

bool ObjectReader::boolean(std::string_view key, bool fallback) {
  const auto* v = find(key);
  if (!v) return fallback;
  if (!v->is_boolean()) fail(key, "must be true or false, got " + short_value(*v));
  return v->get<bool>();
}

std::string ObjectReader::string(std::string_view key, std::string fallback) {
  const auto* v = find(key);
  if (!v) return fallback;
  if (!v->is_string()) fail(key, "must be a string, got " + type_name(*v));
  return v->get<std::string>();
}

std::string ObjectReader::string(std::string_view key) {
  if (!has(key)) {
    known_.emplace(key);
    fail(key, "required string is missing");
  }
  return string(key, std::string());
}

std::string ObjectReader::choice(std::string_view key, std::string fallback,
                                 const std::vector<std::string>& choices) {
  std::string s = string(key, std::move(fallback));
  for (const auto& c : choices) {
    if (c == s) return s;
  }
  std::string list;
  for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c;
  fail(key, "unknown value \"" + s + "\"; valid: " + list);
}

glm::dvec3 ObjectReader::vec3(std::string_view key, glm::dvec3 fallback, Range range) {
  if (!has(key)) {
    known_.emplace(key);
    return fallback;
  }
  return vec3(key, range);
}

glm::dvec3 ObjectReader::vec3(std::string_view key, Range range) {
  const auto* v = find(key);
  if (!v) fail(key, "required [x, y, z] is missing");
  if (!v->is_array() || v->size() != 3) fail(key, "must be an array of 3 numbers");
  glm::dvec3 out;
  for (int i = 0; i < 3; ++i)
    out[i] = checked_number((*v)[i], path_of(key) + "/" + std::to_string(i), range);
  return out;
}

glm::dvec2 ObjectReader::vec2(std::string_view key, glm::dvec2 fallback, Range range) {
  const auto* v = find(key);
  if (!v) return fallback;
  if (!v->is_array() || v->size() != 2) fail(key, "must be an array of 2 numbers");
  glm::dvec2 out;
  for (int i = 0; i < 2; ++i)
    out[i] = checked_number((*v)[i], path_of(key) + "/" + std::to_string(i), range);
  return out;
}

std::vector<double> ObjectReader::numbers(std::string_view key, Range range) {
  const auto* v = find(key);
  if (!v) fail(key, "required array of numbers is missing");
  if (!v->is_array()) fail(key, "must be an array of numbers, got " + type_name(*v));
  std::vector<double> out;
  out.reserve(v->size());
  for (std::size_t i = 0; i < v->size(); ++i) {
    out.push_back(checked_number((*v)[i], path_of(key) + "/" + std::to_string(i), range));
  }
  return out;
}

ObjectReader ObjectReader::object(std::string_view key) {
  const auto* v = find(key);
  if (!v) fail(key, "required object is missing");
  return ObjectReader(*v, file_, path_of(key));
}

std::optional<ObjectReader> ObjectReader::optional_object(std::string_view key) {
  const auto* v = find(key);
  if (!v) return std::nullopt;
  return ObjectReader(*v, file_, path_of(key));
}

std::vector<ObjectReader> ObjectReader::objects(std::string_view key) {
  const auto* v = find(key);
  if (!v) fail(key, "required array is missing");
  if (!v->is_array()) fail(key, "must be an array of objects, got " + type_name(*v));
  std::vector<ObjectReader> out;
  out.reserve(v->size());
  for (std::size_t i = 0; i < v->size(); ++i) {
    out.emplace_back((*v)[i], file_, path_of(key) + "/" + std::to_string(i));
  }
  return out;
}

const nlohmann::json* ObjectReader::raw(std::string_view key) { return find(key); }

void ObjectReader::finish() const {
  for (const auto& [k, v] : j_->items()) {
    if (consumed_.count(k) != 0) continue;
    std::string list;
    for (const auto& known : known_) list += (list.empty() ? "" : ", ") + known;
    throw InputError(file_, path_of(k),
                     "unknown key" + (list.empty() ? std::string() : "; valid keys: " + list));
  }
}

}  // namespace ambisim
