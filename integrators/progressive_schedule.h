#pragma once
// The progressive schedule and the wavelength kernel shared by the consistent estimators: photon
// mapping's gather radius and elastic kernel (docs/photon-mapping.md) and BDPT's spectral
// mollification (docs/bdpt-mis.md §6).

namespace kasha {

// r_i for iteration i ≥ 1 of a kernel over `dimension` dimensions (2: a disc on surfaces, 3: a ball
// in media), from Knaus & Zwicker 2011: the kernel's volume shrinks as r_i^d = r_{i−1}^d·(i − 1 + α)/i
// (their eq. 15 is d = 2; their variance and bias argument holds for any d), in closed form r_i^d = r_1^d·Γ(i + α)/(Γ(1 + α)·Γ(i + 1)), so a resumed render
// needs no history.
float progressiveRadius(float r1, float alpha, int iteration, int dimension);

// r_i² of the two-dimensional schedule (photon discs, vertex merging), r_1²·Γ(i + α)/(Γ(1 + α)·Γ(i + 1)).
float progressiveRadiusSquared(float r1, float alpha, int iteration);

// The Epanechnikov kernel of half-width h in wavelength, per nm: 3/(4h)·(1 − (x/h)²) for |x| < h.
float wavelengthKernel(float x, float h);

// Its mass ∫_lo^hi K_h(x) dx, for the part of the kernel inside the wavelength range.
float wavelengthKernelMass(float lo, float hi, float h);

}  // namespace kasha
