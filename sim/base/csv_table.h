#pragma once
// A small reader for the simulator's CSV outputs (summary.csv, timing.csv): RFC 4180 quoting,
// '#' comment lines skipped, repeated header lines (appended shards) skipped.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace ambisim {

struct CsvTable {
  std::string file;  // where it was read from (for messages)
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;  // every row has header.size() fields

  // Index of a column, or -1.
  int column(std::string_view name) const;
  // Index of a column; throws InputError naming the file if it is missing.
  int require_column(std::string_view name) const;
  // A field as a number: NaN for empty, "nan" or unparsable text.
  double number(std::size_t row, int col) const;
  const std::string& text(std::size_t row, int col) const { return rows[row][col]; }
};

// Splits one CSV line into fields ("" quotes and doubled "" inside quotes).
std::vector<std::string> split_csv_line(std::string_view line);

// Reads a CSV file. Throws InputError naming the file if it is missing, empty, or a row has
// the wrong number of fields.
CsvTable read_csv(const std::string& path);

}  // namespace ambisim
