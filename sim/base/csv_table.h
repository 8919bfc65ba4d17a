#pragma once
// A small strict CSV reader: RFC 4180 quoting, '#' comment lines and blank lines skipped. Used
// for the simulator's own outputs (summary.csv, timing.csv: repeated header lines of appended
// shards are skipped) and for recorded telemetry (sim/scenario/recorded_track.h: a header line
// is required, every field is checked, errors name the file and the line).
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace ambisim {

struct CsvTable {
  std::string file;  // where it was read from (for messages)
  std::vector<std::string> header;
  int header_line = 0;                         // 1-based line of the header (0: none)
  std::vector<std::vector<std::string>> rows;  // every row has header.size() fields
  std::vector<int> lines;                      // 1-based file line of each row

  // Index of a column, or -1.
  int column(std::string_view name) const;
  // Index of a column; throws InputError naming the file if it is missing.
  int require_column(std::string_view name) const;
  // A field as a number: NaN for empty, "nan" or unparsable text.
  double number(std::size_t row, int col) const;
  const std::string& text(std::size_t row, int col) const { return rows[row][col]; }

  // A field as a finite number, strictly: surrounding blanks are ignored, anything else that is
  // not a whole decimal number (empty, "nan", "inf", "1.5x") throws InputError naming the file,
  // the line and the column.
  double finite_number(std::size_t row, int col) const;
  // Checks the header against the columns a format knows: every `required` one present, none
  // twice, none outside required + optional; throws InputError naming the file and the header
  // line, listing the valid columns.
  void check_columns(const std::vector<std::string>& required,
                     const std::vector<std::string>& optional) const;
  // "line N" of a row, for InputError's path slot.
  std::string where(std::size_t row) const;
};

// Splits one CSV line into fields ("" quotes and doubled "" inside quotes).
std::vector<std::string> split_csv_line(std::string_view line);

// Parses CSV text; `file` names it in errors. Throws InputError if there is no header line or a
// row has the wrong number of fields. With `skip_repeated_headers`, a later line equal to the
// header is skipped (shards appended to one file).
CsvTable parse_csv(std::string_view text, const std::string& file,
                   bool skip_repeated_headers = true);

// Reads a CSV file (parse_csv with repeated headers skipped). Throws InputError naming the file
// if it is missing, empty, or a row has the wrong number of fields.
CsvTable read_csv(const std::string& path);

}  // namespace ambisim
