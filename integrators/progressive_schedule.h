#pragma once
// The progressive schedule and the wavelength kernel shared by the consistent estimators: photon
// mapping's gather radius and elastic kernel (docs/photon-mapping.md) and BDPT's spectral
// mollification (docs/bdpt-mis.md §6).

namespace kasha {

// r_i² for iteration i ≥ 1 from Knaus & Zwicker 2011 eq. 15, r_i² = r_{i−1}²·(i − 1 + α)/i, in
// closed form r_i² = r_1²·Γ(i + α)/(Γ(1 + α)·Γ(i + 1)), so a resumed render needs no history.
float progressiveRadiusSquared(float r1, float alpha, int iteration);

// The Epanechnikov kernel of half-width h in wavelength, per nm: 3/(4h)·(1 − (x/h)²) for |x| < h.
float wavelengthKernel(float x, float h);

// Its mass ∫_lo^hi K_h(x) dx, for the part of the kernel inside the wavelength range.
float wavelengthKernelMass(float lo, float hi, float h);

}  // namespace kasha
