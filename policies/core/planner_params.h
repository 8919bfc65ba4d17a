#pragma once
// Declared, validated planner parameters (SimGrid/OMPL style). Each planner declares its
// parameters as specs; a PlannerParams holds values validated against those specs, built from
// a sweep/scenario JSON object (errors name the file and JSON path) or from CLI `--set k=v`
// strings. Unset parameters take their declared default; to_json() echoes every parameter
// with its effective value, so a result always records the full configuration.
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/base/json_reader.h"

namespace ambisim {

enum class ParamType { number, integer, boolean, choice };

std::string to_string(ParamType t);

struct ParamSpec {
  std::string name;
  ParamType type = ParamType::number;
  nlohmann::json default_value;      // double, int64, bool or string, matching `type`
  Range range{};                     // number and integer only
  std::vector<std::string> choices;  // choice only
  std::string description;

  // "> 0", "[0, 1]", "any", "true|false", "one of a, b".
  std::string allowed_text() const;
  // The default as the CLI would take it: "8", "0.5", "true", "nearest".
  std::string default_text() const;
  nlohmann::json to_json() const;
};

ParamSpec number_param(std::string name, double def, Range range, std::string description);
ParamSpec integer_param(std::string name, std::int64_t def, Range range, std::string description);
ParamSpec bool_param(std::string name, bool def, std::string description);
ParamSpec choice_param(std::string name, std::string def, std::vector<std::string> choices,
                       std::string description);

// A CLI value as JSON by its look: true/false -> bool, an integer -> int64, a finite number
// -> double, anything else -> string.
nlohmann::json parse_cli_value(const std::string& text);

class PlannerParams {
 public:
  // No planner bound yet: make_planner() then uses the defaults of whichever planner it builds.
  PlannerParams() = default;
  // All defaults of `planner` (named in error messages).
  PlannerParams(std::string planner, std::vector<ParamSpec> specs);

  // `j` must be an object of parameter values; `pointer` is its JSON path.
  static PlannerParams from_json(std::string planner, std::vector<ParamSpec> specs,
                                 const nlohmann::json& j, const std::string& file,
                                 const std::string& pointer);
  // Each element is "key=value".
  static PlannerParams from_cli(std::string planner, std::vector<ParamSpec> specs,
                                const std::vector<std::string>& assignments);

  // Overrides, validated on the spot (later calls win: scenario file, then --set).
  void set_json(const std::string& key, const nlohmann::json& value, const std::string& file,
                const std::string& path);
  void set_cli(const std::string& assignment);

  // The same explicit values re-validated against another planner's specs (make_planner uses
  // it); errors keep the file/path each value came from.
  PlannerParams bind(std::string planner, std::vector<ParamSpec> specs) const;

  // Effective values; asking for an undeclared name or the wrong type is a programming error
  // (std::logic_error). number() also reads integers.
  double number(std::string_view name) const;
  std::int64_t integer(std::string_view name) const;
  bool boolean(std::string_view name) const;
  std::string choice(std::string_view name) const;

  bool is_set(std::string_view name) const { return explicit_.count(std::string(name)) != 0; }
  const std::string& planner() const { return planner_; }
  const std::vector<ParamSpec>& specs() const { return specs_; }
  // Every declared parameter with its effective value (an object keyed by name).
  nlohmann::json to_json() const;

 private:
  struct Value {
    nlohmann::json value;  // canonical: double, int64, bool or string
    std::string file;      // where it came from, for errors on re-validation
    std::string path;
  };
  const ParamSpec* find(std::string_view name) const;
  const ParamSpec& spec_or_throw(const std::string& key, const std::string& file,
                                 const std::string& path) const;
  const nlohmann::json& effective(std::string_view name, ParamType type) const;

  std::string planner_;
  std::vector<ParamSpec> specs_;
  std::map<std::string, Value, std::less<>> explicit_;
};

}  // namespace ambisim
