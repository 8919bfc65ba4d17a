#pragma once
// Seeded, hash-based 2D noise for terrain and biome masks. Every value depends only on
// (seed, x, y), never on evaluation order, so generation is bit-identical on any schedule.
#include <cstdint>

namespace ambisim {

// Value noise on a unit lattice with quintic fade (C2 continuous); result in [0, 1].
double value_noise(std::uint64_t seed, double x, double y);

// Fractal sum of `octaves` value-noise layers; the first has wavelength `wavelength_m`, each
// next one half the wavelength and `persistence` (0..1) times the amplitude. Result in [0, 1].
double fbm_noise(std::uint64_t seed, double x, double y, double wavelength_m, int octaves,
                 double persistence);

// Ridged multifractal: 1 - |2n - 1| per octave, squared, so sharp crests form where the noise
// crosses its mean. Result in [0, 1].
double ridged_noise(std::uint64_t seed, double x, double y, double wavelength_m, int octaves,
                    double persistence);

}  // namespace ambisim

namespace ambisim {

// Row evaluators: the same values as the point functions above (bit-identical) for every
// x in `xs` at one y, written to `out`. Consecutive x share lattice corners, so the hashes
// are computed once per lattice cell instead of four times per sample.
void value_noise_row(std::uint64_t seed, const double* xs, int n, double y, double* out);
void fbm_noise_row(std::uint64_t seed, const double* xs, int n, double y, double wavelength_m,
                   int octaves, double persistence, double* out);
void ridged_noise_row(std::uint64_t seed, const double* xs, int n, double y, double wavelength_m,
                      int octaves, double persistence, double* out);

}  // namespace ambisim
