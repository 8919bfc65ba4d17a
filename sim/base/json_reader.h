#pragma once
// Strict reading of JSON input into plain records (the pbrt-v4 way: parse and validate first,
// build objects later). Every read names its JSON path; a key that no read consumed is an
// error listing the valid keys, so a typo is never silently ignored.
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "sim/base/input_error.h"

namespace ambisim {

// Parses a whole file. Errors (missing, a directory, unreadable, empty, not JSON) name the file.
nlohmann::json load_json_file(const std::string& path);

// Numeric range for a read; exclusive bounds give "must be > 0" style messages.
struct Range {
  double min = -1e300;
  double max = 1e300;
  bool min_exclusive = false;
  bool max_exclusive = false;
  static Range positive() { return {0.0, 1e300, true, false}; }
  static Range non_negative() { return {0.0, 1e300, false, false}; }
  static Range closed(double lo, double hi) { return {lo, hi, false, false}; }
  static Range unit() { return {0.0, 1.0, false, false}; }
};

class ObjectReader {
 public:
  // `j` must be an object; `pointer` is its JSON path ("" for the document root).
  ObjectReader(const nlohmann::json& j, std::string file, std::string pointer);

  bool has(std::string_view key) const;

  double number(std::string_view key, double fallback, Range range = {});
  double number(std::string_view key, Range range = {});  // required
  int integer(std::string_view key, int fallback, Range range = {});
  int integer(std::string_view key, Range range = {});  // required
  std::uint64_t seed(std::string_view key, std::uint64_t fallback);
  bool boolean(std::string_view key, bool fallback);
  std::string string(std::string_view key, std::string fallback);
  std::string string(std::string_view key);  // required
  // A string that must be one of `choices`; the error lists them.
  std::string choice(std::string_view key, std::string fallback,
                     const std::vector<std::string>& choices);
  glm::dvec3 vec3(std::string_view key, glm::dvec3 fallback, Range range = {});
  glm::dvec3 vec3(std::string_view key, Range range = {});  // required
  glm::dvec2 vec2(std::string_view key, glm::dvec2 fallback, Range range = {});
  std::vector<double> numbers(std::string_view key, Range range = {});  // required array

  // Sub-objects. `object` requires the key; `optional_object` returns nullopt when absent.
  ObjectReader object(std::string_view key);
  std::optional<ObjectReader> optional_object(std::string_view key);
  // An array of objects (required); each element gets its own reader at "/key/i".
  std::vector<ObjectReader> objects(std::string_view key);
  // Raw access for values that are parsed elsewhere; the key counts as consumed.
  const nlohmann::json* raw(std::string_view key);

  // Throws if any key of the object was never read, naming it and listing the valid keys.
  void finish() const;

  const std::string& file() const { return file_; }
  const std::string& pointer() const { return pointer_; }
  std::string path_of(std::string_view key) const;
  [[noreturn]] void fail(std::string_view key, const std::string& message) const;

 private:
  const nlohmann::json* find(std::string_view key);
  double checked_number(const nlohmann::json& v, const std::string& path, Range range) const;

  const nlohmann::json* j_;
  std::string file_;
  std::string pointer_;
  std::set<std::string, std::less<>> consumed_;
  std::set<std::string, std::less<>> known_;
};

}  // namespace ambisim
