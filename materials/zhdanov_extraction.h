#pragma once
// Zhdanov et al.'s recipe (§4–7) for the passive and fluorescent parts of their three-part BDF from
// a fluorimeter measurement R(λ_o; λ_i) of the sample and one R_e of a non-fluorescent etalon with
// known reflectance ρ_e (all matrices in core/bispectral_data.h's layout, on one grid):
//   R̄_e(λ_i) = ∫_{|λ_o−λ_i|≤ε} R_e(λ_o; λ_i) dλ_o / ρ_e(λ_i)   calibration C·F̄_1·I (eqs. 6–7)
//   p(λ_i)   = ∫_{|λ_o−λ_i|≤ε} R(λ_o; λ_i) dλ_o / R̄_e(λ_i)       passive albedo (eq. 7)
//   F(λ_o; λ_i) = R(λ_o; λ_i) / R̄_e(λ_i),  λ_o − λ_i > ε          fluorescence per nm (eq. 8)
//   A(λ_i)   = ∫ F(λ_o; λ_i) dλ_o                                    excitation (eq. 9)
//   E(λ_o)   = ∫ F(λ_o; λ_i) dλ_i / ∫ A(λ_i) dλ_i  over λ_i < λ_o − ε   emission (eq. 9, the
//              A-weighted mean of F/A, so that F = E·A exactly when F factorises; ∫E = 1, eq. 4)
// The matrix holds band values (reflectance factor per output band, as the Labsphere files do), so
// the integrals over λ_o are sums and F = value / Δλ_o. Without an etalon, R̄_e = 1: the matrix is
// taken as already etalon-normalised (a bispectral reflectance factor).
//
// Only the Stokes side (λ_o > λ_i + ε) is fluorescence: values with λ_o < λ_i − ε are noise, and
// the near-diagonal window is the passive part. Values at or below `noiseFloor` (after
// calibration) count as 0 on the fluorescent side; negative values count as 0 everywhere.
// Zhdanov §5 assumes the sensor scale C(λ_o) varies little over the window; off the diagonal it
// must also be nearly constant, which eq. 8 assumes implicitly.
#include <optional>
#include <string>
#include <vector>

#include "core/bispectral_data.h"
#include "core/spectrum.h"

namespace kasha {

struct ExtractionInput {
  BispectralData sample;
  std::optional<BispectralData> etalon;  // same grids as the sample
  Spectrum etalonReflectance = Spectrum::constant(1.0f);  // ρ_e(λ_i)
  float epsilon = 5.0f;     // half-width of the near-diagonal window, nm
  float noiseFloor = 0.0f;  // in calibrated band units
};

struct ZhdanovFit {
  std::vector<float> in, out;         // λ_i and λ_o grids of the measurement
  std::vector<float> passive;         // p at each λ_i (0 where no output lies within ε)
  std::vector<float> excitation;      // A at each λ_i
  std::vector<float> emission;        // E per nm at each λ_o, Σ E·Δλ_o = 1 (0 if nothing fluoresces)
  std::vector<bool> passiveMeasured;  // whether λ_i had outputs within ε
  // Inputs with data but no output within ε, which an etalon cannot calibrate: left out (p = A = 0).
  std::vector<float> uncalibrated;
  // ‖F − E·A‖ / ‖F‖ over the Stokes cells (Frobenius norms of the per-nm densities): how well the
  // factorisation (eq. 3) explains the measured fluorescence. 0 when it holds exactly.
  double residual = 0.0;
  // Fraction of the factorised fluorescence E·A that falls on cells with λ_o ≤ λ_i + ε, where the
  // measurement has no fluorescence (the model re-emits there although the sample cannot be seen to).
  double unmeasuredFraction = 0.0;
};

// Throws InputError naming the file and the reason (grids that differ, an etalon without signal
// near the diagonal where the sample has data).
ZhdanovFit extractZhdanov(const ExtractionInput& input);

}  // namespace kasha
