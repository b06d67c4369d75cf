#include "materials/ior.h"

#include <cmath>
#include <sstream>

namespace kasha {

Ior Ior::constant(double n) { return Ior(Form::Constant, {n, 0.0, 0.0}, {}); }

Ior Ior::cauchy(double a, double b, double c) { return Ior(Form::Cauchy, {a, b, c}, {}); }

Ior Ior::sellmeier(const std::array<double, 3>& b, const std::array<double, 3>& c) {
  return Ior(Form::Sellmeier, b, c);
}

std::optional<Ior> Ior::preset(const std::string& name) {
  // Schott N-BK7 data sheet coefficients.
  if (name == "BK7") return sellmeier({1.03961212, 0.231792344, 1.01046945}, {0.00600069867, 0.0200179144, 103.560653});
  // Malitson 1965, eq. 2: resonance wavelengths 0.0684043, 0.1162414 and 9.896161 µm, squared.
  if (name == "fused_silica")
    return sellmeier({0.6961663, 0.4079426, 0.8974794}, {0.0684043 * 0.0684043, 0.1162414 * 0.1162414, 9.896161 * 9.896161});
  return std::nullopt;
}

const std::vector<std::string>& Ior::presetNames() {
  static const std::vector<std::string> names = {"BK7", "fused_silica"};
  return names;
}

float Ior::operator()(float lambdaNm) const {
  const double l2 = double(lambdaNm) * double(lambdaNm) * 1e-6;  // λ² in µm²
  switch (form_) {
    case Form::Constant:
      return float(b_[0]);
    case Form::Cauchy:
      return float(b_[0] + b_[1] / l2 + b_[2] / (l2 * l2));
    case Form::Sellmeier: {
      double n2 = 1.0;
      for (int i = 0; i < 3; ++i) n2 += b_[i] * l2 / (l2 - c_[i]);
      return float(std::sqrt(n2));  // NaN where n² < 0: checkIor rejects it
    }
  }
  return 0.0f;
}

bool Ior::dispersive() const {
  switch (form_) {
    case Form::Constant:
      return false;
    case Form::Cauchy:
      return b_[1] != 0.0 || b_[2] != 0.0;
    case Form::Sellmeier:
      return b_[0] != 0.0 || b_[1] != 0.0 || b_[2] != 0.0;
  }
  return false;
}

std::string Ior::describe() const {
  std::ostringstream s;
  switch (form_) {
    case Form::Constant:
      s << "n = " << b_[0];
      break;
    case Form::Cauchy:
      s << "Cauchy A = " << b_[0] << ", B = " << b_[1] << " µm², C = " << b_[2] << " µm⁴";
      break;
    case Form::Sellmeier:
      s << "Sellmeier B = [" << b_[0] << ", " << b_[1] << ", " << b_[2] << "], C = [" << c_[0] << ", " << c_[1]
        << ", " << c_[2] << "] µm²";
      break;
  }
  return s.str();
}

std::vector<double> Ior::polesNm() const {
  std::vector<double> poles;
  if (form_ == Form::Sellmeier)
    for (int i = 0; i < 3; ++i)
      if (c_[i] > 0.0 && b_[i] != 0.0) poles.push_back(std::sqrt(c_[i]) * 1000.0);
  return poles;
}

std::string checkIor(const Ior& ior, WavelengthRange range) {
  for (double pole : ior.polesNm())
    if (pole >= range.min && pole <= range.max)
      return "Sellmeier pole at " + std::to_string(pole) + " nm (λ² = C) inside the wavelength range";
  auto check = [&](float l) -> std::string {
    const float n = ior(l);
    const std::string at = ior.dispersive() ? " at " + std::to_string(l) + " nm" : "";
    if (!std::isfinite(n)) return "index of refraction is not a finite real number" + at;
    if (n < 1.0f) return "index of refraction " + std::to_string(n) + at + " is below 1";
    return {};
  };
  for (float l = std::ceil(range.min); l <= range.max; l += 1.0f)
    if (std::string m = check(l); !m.empty()) return m;
  for (float l : {range.min, range.max})
    if (std::string m = check(l); !m.empty()) return m;
  return {};
}

}  // namespace kasha
