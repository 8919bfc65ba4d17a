#include "policies/core/planner_params.h"

#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "sim/base/input_error.h"

namespace ambisim {
namespace {

// Range's open ends are +-1e300 (or infinities).
bool has_lower(const Range& r) { return std::isfinite(r.min) && r.min > -1e299; }
bool has_upper(const Range& r) { return std::isfinite(r.max) && r.max < 1e299; }

std::string format_number(double x) {
  std::ostringstream os;
  os.precision(12);
  os << x;
  return os.str();
}

std::string format_value(const nlohmann::json& v) {
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_number_integer()) return std::to_string(v.get<std::int64_t>());
  if (v.is_number()) return format_number(v.get<double>());
  if (v.is_string()) {
    // Appended rather than "\"" + s + "\"": GCC 12 -O3 warns falsely (-Wrestrict, PR105329).
    std::string q(1, '"');
    q.append(v.get<std::string>()).push_back('"');
    return q;
  }
  std::string s = v.dump();
  return s.size() > 40 ? s.substr(0, 37) + "..." : s;
}

// Like format_value, but strings bare (for "key=value" lists).
std::string format_default(const nlohmann::json& v) {
  return v.is_string() ? v.get<std::string>() : format_value(v);
}

std::string join(const std::vector<std::string>& items, const char* sep) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : sep) + s;
  return out;
}

// "a number > 0", "an integer in [1, 4096]", "true or false", "one of a, b".
std::string expectation(const ParamSpec& s) {
  switch (s.type) {
    case ParamType::number:
    case ParamType::integer: {
      std::string e = s.type == ParamType::number ? "a number" : "an integer";
      const std::string allowed = s.allowed_text();
      if (allowed == "any") return e;
      return e + (allowed[0] == '[' || allowed[0] == '(' ? " in " : " ") + allowed;
    }
    case ParamType::boolean:
      return "true or false";
    case ParamType::choice:
      return s.allowed_text();
  }
  return "";
}

bool in_range(double x, const Range& r) {
  const bool low = r.min_exclusive ? !(x > r.min) : !(x >= r.min);
  const bool high = r.max_exclusive ? !(x < r.max) : !(x <= r.max);
  return !low && !high;
}

std::string owner_text(const std::string& planner) {
  return planner.empty() ? std::string() : " of planner \"" + planner + "\"";
}

// The canonical value of `v` for `s`, or an InputError naming the parameter and what is allowed.
nlohmann::json validate(const ParamSpec& s, const nlohmann::json& v, const std::string& planner,
                        const std::string& file, const std::string& path) {
  bool ok = false;
  nlohmann::json out;
  switch (s.type) {
    case ParamType::number:
      if (v.is_number() && std::isfinite(v.get<double>()) && in_range(v.get<double>(), s.range)) {
        ok = true;
        out = v.get<double>();
      }
      break;
    case ParamType::integer:
      if (v.is_number_integer() && in_range(static_cast<double>(v.get<std::int64_t>()), s.range)) {
        ok = true;
        out = v.get<std::int64_t>();
      }
      break;
    case ParamType::boolean:
      if (v.is_boolean()) {
        ok = true;
        out = v;
      }
      break;
    case ParamType::choice:
      if (v.is_string()) {
        for (const auto& c : s.choices) ok = ok || c == v.get<std::string>();
        out = v;
      }
      break;
  }
  if (!ok) {
    throw InputError(file, path,
                     "parameter \"" + s.name + "\"" + owner_text(planner) + " must be " +
                         expectation(s) + ", got " + format_value(v));
  }
  return out;
}

}  // namespace

std::string to_string(ParamType t) {
  switch (t) {
    case ParamType::number:
      return "number";
    case ParamType::integer:
      return "integer";
    case ParamType::boolean:
      return "bool";
    case ParamType::choice:
      return "choice";
  }
  return "?";
}

std::string ParamSpec::allowed_text() const {
  switch (type) {
    case ParamType::boolean:
      return "true|false";
    case ParamType::choice:
      return "one of " + join(choices, ", ");
    case ParamType::number:
    case ParamType::integer:
      break;
  }
  const bool lo = has_lower(range), hi = has_upper(range);
  if (lo && hi) {
    return std::string(range.min_exclusive ? "(" : "[") + format_number(range.min) + ", " +
           format_number(range.max) + (range.max_exclusive ? ")" : "]");
  }
  if (lo) return std::string(range.min_exclusive ? "> " : ">= ") + format_number(range.min);
  if (hi) return std::string(range.max_exclusive ? "< " : "<= ") + format_number(range.max);
  return "any";
}

std::string ParamSpec::default_text() const { return format_default(default_value); }

nlohmann::json ParamSpec::to_json() const {
  nlohmann::json j = {{"name", name},
                      {"type", to_string(type)},
                      {"default", default_value},
                      {"allowed", allowed_text()},
                      {"description", description}};
  if (type == ParamType::choice) j["choices"] = choices;
  return j;
}

ParamSpec number_param(std::string name, double def, Range range, std::string description) {
  return {std::move(name), ParamType::number, def, range, {}, std::move(description)};
}

ParamSpec integer_param(std::string name, std::int64_t def, Range range, std::string description) {
  return {std::move(name), ParamType::integer, def, range, {}, std::move(description)};
}

ParamSpec bool_param(std::string name, bool def, std::string description) {
  return {std::move(name), ParamType::boolean, def, {}, {}, std::move(description)};
}

ParamSpec choice_param(std::string name, std::string def, std::vector<std::string> choices,
                       std::string description) {
  return {std::move(name),    ParamType::choice,     std::move(def), {},
          std::move(choices), std::move(description)};
}

nlohmann::json parse_cli_value(const std::string& text) {
  if (text == "true") return true;
  if (text == "false") return false;
  const char* first = text.data();
  const char* last = first + text.size();
  if (!text.empty()) {
    std::int64_t i = 0;
    auto [pi, ei] = std::from_chars(first, last, i);
    if (ei == std::errc() && pi == last) return i;
    double d = 0.0;
    auto [pd, ed] = std::from_chars(first, last, d);
    if (ed == std::errc() && pd == last && std::isfinite(d)) return d;
  }
  return text;
}

PlannerParams::PlannerParams(std::string planner, std::vector<ParamSpec> specs)
    : planner_(std::move(planner)), specs_(std::move(specs)) {}

PlannerParams PlannerParams::from_json(std::string planner, std::vector<ParamSpec> specs,
                                       const nlohmann::json& j, const std::string& file,
                                       const std::string& pointer) {
  const ObjectReader reader(j, file, pointer);  // rejects a non-object, naming the path
  PlannerParams p(std::move(planner), std::move(specs));
  for (const auto& [key, value] : j.items()) p.set_json(key, value, file, reader.path_of(key));
  return p;
}

PlannerParams PlannerParams::from_cli(std::string planner, std::vector<ParamSpec> specs,
                                      const std::vector<std::string>& assignments) {
  PlannerParams p(std::move(planner), std::move(specs));
  for (const auto& a : assignments) p.set_cli(a);
  return p;
}

const ParamSpec* PlannerParams::find(std::string_view name) const {
  for (const auto& s : specs_) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

const ParamSpec& PlannerParams::spec_or_throw(const std::string& key, const std::string& file,
                                              const std::string& path) const {
  if (const ParamSpec* s = find(key)) return *s;
  const std::string who =
      planner_.empty() ? std::string("this planner") : "planner \"" + planner_ + "\"";
  if (specs_.empty()) {
    throw InputError(file, path,
                     "unknown parameter \"" + key + "\": " + who + " has no parameters");
  }
  std::vector<std::string> valid;
  for (const auto& s : specs_) valid.push_back(s.name + "=" + s.default_text());
  throw InputError(file, path,
                   "unknown parameter \"" + key + "\" for " + who +
                       "; valid parameters (defaults): " + join(valid, ", "));
}

void PlannerParams::set_json(const std::string& key, const nlohmann::json& value,
                             const std::string& file, const std::string& path) {
  const ParamSpec& s = spec_or_throw(key, file, path);
  explicit_[key] = Value{validate(s, value, planner_, file, path), file, path};
}

void PlannerParams::set_cli(const std::string& assignment) {
  const std::string file = "--set " + assignment;
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw InputError(file, "", "expected key=value");
  }
  const std::string key = assignment.substr(0, eq);
  const std::string text = assignment.substr(eq + 1);
  const ParamSpec& s = spec_or_throw(key, file, "");
  // A choice is a string even when it looks like a number ("--set mode=2d").
  const nlohmann::json v =
      s.type == ParamType::choice ? nlohmann::json(text) : parse_cli_value(text);
  explicit_[key] = Value{validate(s, v, planner_, file, ""), file, ""};
}

PlannerParams PlannerParams::bind(std::string planner, std::vector<ParamSpec> specs) const {
  PlannerParams p(std::move(planner), std::move(specs));
  for (const auto& [key, v] : explicit_) p.set_json(key, v.value, v.file, v.path);
  return p;
}

const nlohmann::json& PlannerParams::effective(std::string_view name, ParamType type) const {
  const ParamSpec* s = find(name);
  if (!s) {
    throw std::logic_error("planner \"" + planner_ + "\" reads undeclared parameter \"" +
                           std::string(name) + "\"");
  }
  const bool ok = s->type == type || (type == ParamType::number && s->type == ParamType::integer);
  if (!ok) {
    throw std::logic_error("parameter \"" + s->name + "\" is a " + to_string(s->type) +
                           ", read as a " + to_string(type));
  }
  auto it = explicit_.find(name);
  return it == explicit_.end() ? s->default_value : it->second.value;
}

double PlannerParams::number(std::string_view name) const {
  return effective(name, ParamType::number).get<double>();
}

std::int64_t PlannerParams::integer(std::string_view name) const {
  return effective(name, ParamType::integer).get<std::int64_t>();
}

bool PlannerParams::boolean(std::string_view name) const {
  return effective(name, ParamType::boolean).get<bool>();
}

std::string PlannerParams::choice(std::string_view name) const {
  return effective(name, ParamType::choice).get<std::string>();
}

nlohmann::json PlannerParams::to_json() const {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& s : specs_) {
    auto it = explicit_.find(s.name);
    j[s.name] = it == explicit_.end() ? s.default_value : it->second.value;
  }
  return j;
}

}  // namespace ambisim
