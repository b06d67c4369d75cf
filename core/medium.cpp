#include "core/medium.h"

#include <cmath>
#include <stdexcept>

namespace kasha {
namespace {

// "" if s is finite and non-negative over the range, else "field: reason".
std::string checkCoefficient(const Spectrum& s, WavelengthRange range, const std::string& field) {
  const float lo = s.minValue(range.min, range.max), hi = s.maxValue(range.min, range.max);
  if (!(lo >= 0.0f)) return field + ": negative or NaN value in the wavelength range";
  if (!std::isfinite(hi)) return field + ": infinite value in the wavelength range";
  return {};
}

}  // namespace

std::string checkMediumParams(const MediumParams& p, WavelengthRange range) {
  if (std::string m = checkCoefficient(p.absorption, range, "sigma_a"); !m.empty()) return m;
  if (std::string m = checkCoefficient(p.scattering, range, "sigma_s"); !m.empty()) return m;
  if (!(p.g > -1.0f && p.g < 1.0f)) return "g: " + std::to_string(p.g) + " is outside (-1, 1)";
  for (size_t k = 0; k < p.fluorophores.size(); ++k) {
    const Fluorophore& f = p.fluorophores[k];
    const std::string at = "fluorophores[" + std::to_string(k) + "].";
    if (std::string m = checkCoefficient(f.absorption, range, at + "sigma_f"); !m.empty()) return m;
    if (!(f.yield >= 0.0f && f.yield <= 1.0f)) return at + "yield: " + std::to_string(f.yield) + " is outside [0, 1]";
    if (std::string m = checkCoefficient(f.emission, range, at + "emission"); !m.empty()) return m;
    if (!(f.emission.integral(range) > 0.0f)) return at + "emission: integrates to zero over the wavelength range";
  }
  // σ_t (eq. 1) must stay finite too: an infinite one turns every flight's weight T/p into 0.
  float sigmaT = p.absorption.maxValue(range.min, range.max);
  const auto overflows = [&](const Spectrum& s) { return !std::isfinite(sigmaT += s.maxValue(range.min, range.max)); };
  if (overflows(p.scattering)) return "sigma_s: sigma_t = sigma_a + sigma_s + sum of sigma_f overflows a 32-bit float";
  for (size_t k = 0; k < p.fluorophores.size(); ++k)
    if (overflows(p.fluorophores[k].absorption))
      return "fluorophores[" + std::to_string(k) + "].sigma_f: sigma_t = sigma_a + sigma_s + sum of sigma_f overflows a 32-bit float";
  return {};
}

Medium::Medium(std::string name, MediumParams params, WavelengthRange range,
               std::shared_ptr<const DensityField> density, std::shared_ptr<const AlbedoField> albedo)
    : name_(std::move(name)), params_(std::move(params)), range_(range), density_(std::move(density)),
      albedo_(std::move(albedo)) {
  if (std::string m = checkMediumParams(params_, range_); !m.empty()) throw std::invalid_argument(m);
  // Camera paths seek a fluorescent medium's source with a second free-flight density (media.md
  // eq. 6b), which delta tracking against one majorant does not combine with yet.
  if (density_ && !params_.fluorophores.empty())
    throw std::invalid_argument("fluorophores: a heterogeneous medium cannot fluoresce yet (media.md §4)");
  // An albedo field splits the one σ_t of a homogeneous medium (eq. 7): no density scales it, no
  // fluorophore shares it.
  if (albedo_ && density_) throw std::invalid_argument("albedo_grid: a heterogeneous medium has no albedo field (media.md §7)");
  if (albedo_ && !params_.fluorophores.empty())
    throw std::invalid_argument("albedo_grid: a fluorescent medium has no albedo field (media.md §7)");
  for (const Fluorophore& f : params_.fluorophores) {
    absorption_.emplace_back(f.absorption, range_);
    emission_.emplace_back(f.emission, range_);
    fluorescent_ = fluorescent_ || (f.yield > 0.0f && absorption_.back().integral() > 0.0f);
  }
}

float Medium::sigmaT(float lambda) const {
  float s = sigmaA(lambda) + sigmaS(lambda);
  for (const Fluorophore& f : params_.fluorophores) s += f.absorption(lambda);
  return s;
}

}  // namespace kasha
