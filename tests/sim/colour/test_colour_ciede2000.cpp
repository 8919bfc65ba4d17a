// CIEDE2000 against the published Sharma, Wu & Dalal (2005) test pairs, in both orders.
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "sim/colour/ciede2000.h"

using ambisim::Lab;

namespace {
// The table gives dE00 to 4 decimals (rounding error <= 5e-5). Measured max |error| over the
// 34 pairs in both orders: 4.95e-5, i.e. table rounding only.
constexpr double kDe00TableTol = 1e-4;
// Closed forms below are exact up to double rounding.
constexpr double kDe00ExactTol = 1e-12;

struct SharmaPair {
  Lab lab1, lab2;
  double de00;
};

std::vector<SharmaPair> read_sharma_table() {
  std::ifstream in(std::string(AMBISIM_SHARED_DATA_DIR) + "/ciede2000_sharma2005.csv");
  REQUIRE(in.good());
  std::vector<SharmaPair> rows;
  std::string line;
  bool header_seen = false;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (!header_seen) {  // "L1,a1,b1,L2,a2,b2,dE00"
      header_seen = true;
      continue;
    }
    std::istringstream ss(line);
    double v[7];
    char comma = 0;
    for (int k = 0; k < 7; ++k) {
      ss >> v[k];
      if (k < 6) ss >> comma;
      REQUIRE(!ss.fail());
    }
    rows.push_back({{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, v[6]});
  }
  return rows;
}
}  // namespace

TEST_CASE("CIEDE2000 reproduces the Sharma 2005 table in both orders", "[colour]") {
  const auto rows = read_sharma_table();
  REQUIRE(rows.size() == 34);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    INFO("pair " << k + 1);
    const double d12 = ambisim::ciede2000(rows[k].lab1, rows[k].lab2);
    const double d21 = ambisim::ciede2000(rows[k].lab2, rows[k].lab1);
    CHECK(d12 == Approx(rows[k].de00).margin(kDe00TableTol));
    CHECK(d21 == Approx(rows[k].de00).margin(kDe00TableTol));
  }
}

TEST_CASE("CIEDE2000 closed forms: identity, pure lightness, weights", "[colour]") {
  const Lab c{61.2901, 3.7196, -5.3901};
  CHECK(ambisim::ciede2000(c, c) == 0.0);
  // Achromatic pair: only the lightness term, dE = |dL| / S_L with L' = 55:
  // S_L = 1 + 0.015 * 25 / sqrt(20 + 25).
  const double s_l = 1.0 + 0.015 * 25.0 / std::sqrt(45.0);
  CHECK(ambisim::ciede2000({50, 0, 0}, {60, 0, 0}) == Approx(10.0 / s_l).margin(kDe00ExactTol));
  CHECK(ambisim::ciede2000({50, 0, 0}, {60, 0, 0}, {2.0, 1.0, 1.0}) ==
        Approx(5.0 / s_l).margin(kDe00ExactTol));
  // At L' = 50, S_L = 1: a lightness step of 1 is exactly one unit.
  CHECK(ambisim::ciede2000({49.5, 0, 0}, {50.5, 0, 0}) == Approx(1.0).margin(kDe00ExactTol));
}
