#pragma once
// CIEDE2000 colour difference (CIE 142-2001), implemented after Sharma, Wu & Dalal,
// "The CIEDE2000 color-difference formula: implementation notes, supplementary test data, and
// mathematical observations", Color Res. Appl. 30(1), 2005. Double precision throughout.
//
// dE00 ~ 1 is about one just-noticeable difference for surface colours.
#include "sim/colour/cielab.h"

namespace ambisim {

// Parametric weights; 1, 1, 1 are the reference conditions (and what the metrics use).
struct Ciede2000Weights {
  double k_l = 1.0;
  double k_c = 1.0;
  double k_h = 1.0;
};

// Difference between two Lab colours (any finite values; L in [0, 100] in practice).
// Symmetric up to rounding, >= 0, and 0 for equal inputs.
double ciede2000(const Lab& lab1, const Lab& lab2, const Ciede2000Weights& w = {});

}  // namespace ambisim
