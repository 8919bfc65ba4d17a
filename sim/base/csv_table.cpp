#include "sim/base/csv_table.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "sim/base/input_error.h"

namespace ambisim {
namespace {

std::string_view trimmed(std::string_view s) {
  const std::size_t a = s.find_first_not_of(" \t");
  if (a == std::string_view::npos) return {};
  const std::size_t b = s.find_last_not_of(" \t");
  return s.substr(a, b - a + 1);
}

std::string quoted_short(std::string_view s) {
  std::string out(s.substr(0, 40));
  if (s.size() > 40) out += "...";
  return "'" + out + "'";
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

int CsvTable::column(std::string_view name) const {
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (header[i] == name) return static_cast<int>(i);
  }
  return -1;
}

int CsvTable::require_column(std::string_view name) const {
  const int c = column(name);
  if (c < 0) throw InputError(file, "", "missing column '" + std::string(name) + "'");
  return c;
}

double CsvTable::number(std::size_t row, int col) const {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (col < 0 || row >= rows.size()) return nan;
  const std::string& s = rows[row][static_cast<std::size_t>(col)];
  if (s.empty()) return nan;
  double v = nan;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || ptr != s.data() + s.size()) return nan;
  return v;
}

std::string CsvTable::where(std::size_t row) const {
  return "line " + std::to_string(row < lines.size() ? lines[row] : 0);
}

double CsvTable::finite_number(std::size_t row, int col) const {
  const std::string_view s = trimmed(rows.at(row).at(static_cast<std::size_t>(col)));
  const std::string name = header[static_cast<std::size_t>(col)];
  if (s.empty()) throw InputError(file, where(row), name + ": empty; expected a number");
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec == std::errc::result_out_of_range) {
    throw InputError(file, where(row), name + ": " + quoted_short(s) + " is out of range");
  }
  if (ec != std::errc() || ptr != s.data() + s.size() || !std::isfinite(v)) {
    throw InputError(file, where(row), name + ": not a number: " + quoted_short(s));
  }
  return v;
}

void CsvTable::check_columns(const std::vector<std::string>& required,
                             const std::vector<std::string>& optional) const {
  const std::string at = "line " + std::to_string(header_line);
  std::vector<std::string> valid = required;
  valid.insert(valid.end(), optional.begin(), optional.end());
  for (std::size_t i = 0; i < header.size(); ++i) {
    bool known = false;
    for (const auto& v : valid) known = known || v == header[i];
    if (!known) {
      throw InputError(file, at,
                       "unknown column " + quoted_short(header[i]) +
                           "; valid columns: " + joined(valid) + " (a header line is required)");
    }
    for (std::size_t k = 0; k < i; ++k) {
      if (header[k] == header[i]) {
        throw InputError(file, at, "column " + quoted_short(header[i]) + " appears twice");
      }
    }
  }
  for (const auto& r : required) {
    if (column(r) < 0) {
      throw InputError(
          file, at,
          "missing column '" + r + "'; the header needs " + joined(required) +
              (optional.empty() ? std::string() : " (optional: " + joined(optional) + ")"));
    }
  }
}

std::vector<std::string> split_csv_line(std::string_view line) {
  std::vector<std::string> out;
  std::string field;
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char ch = line[i];
    if (quoted) {
      if (ch == '"') {
        if (i + 1 < line.size() && line[i + 1] == '"') {
          field += '"';
          ++i;
        } else {
          quoted = false;
        }
      } else {
        field += ch;
      }
    } else if (ch == '"') {
      quoted = true;
    } else if (ch == ',') {
      out.push_back(std::move(field));
      field.clear();
    } else if (ch != '\r') {
      field += ch;
    }
  }
  out.push_back(std::move(field));
  return out;
}

CsvTable parse_csv(std::string_view text, const std::string& file, bool skip_repeated_headers) {
  CsvTable t;
  t.file = file;
  std::string header_line;
  int line_no = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (trimmed(line).empty() || line[0] == '#') continue;
    if (t.header.empty()) {
      header_line = line;
      t.header_line = line_no;
      t.header = split_csv_line(line);
      for (auto& h : t.header) h = std::string(trimmed(h));
      continue;
    }
    if (skip_repeated_headers && line == header_line) continue;
    auto fields = split_csv_line(line);
    if (fields.size() != t.header.size()) {
      throw InputError(file, "line " + std::to_string(line_no),
                       "has " + std::to_string(fields.size()) + " fields, the header has " +
                           std::to_string(t.header.size()));
    }
    t.rows.push_back(std::move(fields));
    t.lines.push_back(line_no);
  }
  if (t.header.empty()) throw InputError(file, "", "empty CSV file (no header)");
  return t;
}

CsvTable read_csv(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot open (missing or unreadable)");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return parse_csv(buffer.str(), path);
}

}  // namespace ambisim
