// The CSV reader: line numbers of rows, repeated headers skipped only when asked, strict
// numbers and column checks that name the file and the line.
#include <catch2/catch.hpp>

#include "sim/base/csv_table.h"
#include "sim/base/input_error.h"

using namespace ambisim;

TEST_CASE("parse_csv keeps each row's line and skips comments and blank lines", "[csv]") {
  const CsvTable t = parse_csv("# note\n\na,b\n1,2\n\n3,\"4,5\"\na,b\n6,7\n", "t.csv");
  CHECK(t.header == std::vector<std::string>{"a", "b"});
  CHECK(t.header_line == 3);
  REQUIRE(t.rows.size() == 3);  // the repeated header is skipped
  CHECK(t.lines == std::vector<int>{4, 6, 8});
  CHECK(t.text(1, 1) == "4,5");
  CHECK(t.where(2) == "line 8");
  const CsvTable strict = parse_csv("a,b\n1,2\na,b\n", "t.csv", false);
  REQUIRE(strict.rows.size() == 2);
  CHECK(strict.text(1, 0) == "a");
  CHECK_THROWS_WITH(parse_csv("a,b\n1,2,3\n", "t.csv"),
                    "t.csv: line 2: has 3 fields, the header has 2");
  CHECK_THROWS_WITH(parse_csv("\n# only\n", "t.csv"), "t.csv: empty CSV file (no header)");
}

TEST_CASE("finite_number and check_columns are strict", "[csv]") {
  const CsvTable t = parse_csv("time,x\n 1.5 ,abc\n2,inf\n", "t.csv");
  CHECK(t.finite_number(0, 0) == 1.5);
  CHECK_THROWS_WITH(t.finite_number(0, 1), "t.csv: line 2: x: not a number: 'abc'");
  CHECK_THROWS_WITH(t.finite_number(1, 1), "t.csv: line 3: x: not a number: 'inf'");
  CHECK_NOTHROW(t.check_columns({"time", "x"}, {}));
  CHECK_NOTHROW(t.check_columns({"time"}, {"x", "y"}));
  CHECK_THROWS_WITH(t.check_columns({"time", "x", "y"}, {}),
                    "t.csv: line 1: missing column 'y'; the header needs time, x, y");
  CHECK_THROWS_WITH(t.check_columns({"time"}, {}),
                    "t.csv: line 1: unknown column 'x'; valid columns: time (a header line is "
                    "required)");
}
