#include "sim/base/csv_table.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>

#include "sim/base/input_error.h"

namespace ambisim {

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

CsvTable read_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "cannot open (missing or unreadable)");
  CsvTable t;
  t.file = path;
  std::string line;
  std::string header_line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    if (t.header.empty()) {
      header_line = line;
      t.header = split_csv_line(line);
      continue;
    }
    if (line == header_line) continue;
    auto fields = split_csv_line(line);
    if (fields.size() != t.header.size()) {
      throw InputError(path, "",
                       "line " + std::to_string(line_no) + " has " + std::to_string(fields.size()) +
                           " fields, the header has " + std::to_string(t.header.size()));
    }
    t.rows.push_back(std::move(fields));
  }
  if (t.header.empty()) throw InputError(path, "", "empty CSV file (no header)");
  return t;
}

}  // namespace ambisim
