#pragma once
// Index of refraction n(λ) of a dielectric relative to the vacuum outside it. Three forms, each
// with λ in micrometres (the convention of glass catalogues), evaluated from nm:
//   constant   n
//   Cauchy     n = A + B/λ² + C/λ⁴                      B in µm², C in µm⁴
//   Sellmeier  n² = 1 + Σ_{i=1..3} B_i·λ²/(λ² − C_i)     C_i in µm² (the Schott catalogue form)
// and presets of the Sellmeier form:
//   "BK7"           Schott N-BK7 (Schott optical glass data sheet; n_d = 1.5168 at 587.6 nm)
//   "fused_silica"  Malitson 1965, "Interspecimen comparison of the refractive index of fused
//                   silica", JOSA 55(10), 1205 (n_d = 1.4585)
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/spectrum.h"

namespace kasha {

class Ior {
 public:
  static Ior constant(double n);
  static Ior cauchy(double a, double b, double c);
  static Ior sellmeier(const std::array<double, 3>& b, const std::array<double, 3>& c);
  // nullopt for an unknown name.
  static std::optional<Ior> preset(const std::string& name);
  static const std::vector<std::string>& presetNames();

  // n at a wavelength in nm.
  float operator()(float lambdaNm) const;
  // True if n depends on λ (so refraction disperses).
  bool dispersive() const;
  std::string describe() const;

  // Wavelengths (nm) where the Sellmeier form has a pole (λ² = C_i > 0); empty for the others.
  std::vector<double> polesNm() const;

 private:
  enum class Form { Constant, Cauchy, Sellmeier };
  Ior(Form form, std::array<double, 3> b, std::array<double, 3> c) : form_(form), b_(b), c_(c) {}
  Form form_;
  std::array<double, 3> b_;  // constant: {n, 0, 0}; Cauchy: {A, B, C}; Sellmeier: B_1..B_3
  std::array<double, 3> c_;  // Sellmeier: C_1..C_3 in µm²
};

// Empty if n(λ) is finite and at least 1 at every whole nm of the range and at its ends, with no
// Sellmeier pole inside the range; else the reason, for an error message.
std::string checkIor(const Ior& ior, WavelengthRange range);

}  // namespace kasha
