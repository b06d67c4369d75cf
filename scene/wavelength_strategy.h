#pragma once
// Wavelength sampling strategies (docs/wavelength-sampling.md): where a wavelength is drawn — at
// the sensor, for the excitation wavelength at a fluorescent event of a camera path, or at the
// start of a light subpath — kasha can draw it from uniform, colour-matching, light-power,
// fluorophore absorption or emission densities, Yamamoto et al.'s mixture, and MIS combinations
// of these (core/wavelength_spec.h).
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "core/wavelength_density.h"
#include "core/wavelength_spec.h"

namespace kasha {

// Nee: the excitation wavelength of next-event estimation from a fluorescent vertex, drawn apart
// from the event's own (path tracer).
enum class WavelengthSite { Sensor, Fluorescence, LightStart, Nee };
const char* toString(WavelengthSite s);
// The render setting that chooses the strategy of a site: "sensor_sampling",
// "fluorescence_sampling", "light_sampling" or "nee_sampling" (command-line option: the same with
// dashes).
const char* settingName(WavelengthSite s);

// A strategy that does not apply to the scene, the site or the integrator.
class WavelengthStrategyError : public std::invalid_argument {
 public:
  WavelengthStrategyError(WavelengthSite site, const std::string& reason)
      : std::invalid_argument(reason), site_(site) {}
  WavelengthSite site() const { return site_; }

 private:
  WavelengthSite site_;
};

// The spectra of a scene that strategies are built from, gathered once.
struct WavelengthSources {
  explicit WavelengthSources(const Scene& scene);

  struct Fluorophore {
    size_t material = 0;
    FluorophoreSpectra spectra;
    float area = 0.0f;  // total area of the shapes made of it
  };
  WavelengthRange range;  // the scene's
  WavelengthRange seen;   // the part of it where the CIE observer is non-zero
  // Where a site's densities live: the sensor spends no sample where the observer is blind.
  WavelengthRange rangeOf(WavelengthSite site) const { return site == WavelengthSite::Sensor ? seen : range; }
  Spectrum lightPower;  // Σ_l Φ_l(λ)
  std::shared_ptr<const SpectralDistribution> colorMatching;  // x̄ + ȳ + z̄ over `seen`
  std::vector<Fluorophore> fluorophores;  // every fluorescent material's (Material::fluorophore)
  // Light that can exist at λ anywhere in the scene: emitted by a light or re-emitted by a
  // fluorophore. A density must cover it wherever the integrand needs it.
  Spectrum reachable;

  const Fluorophore* fluorophoreOf(size_t material) const;
};

// Yamamoto et al.'s per-fluorophore weights of p_F(λ) = Σ_t w_Ft·F_t(λ)/k_Ft: proportional to the
// area A_t of the objects holding fluorophore t and to k_Ft = ∫F_t dλ, so that p_F ∝ Σ_t A_t·F_t.
std::vector<float> yamamotoFluorophoreWeights(const std::vector<float>& areas, const std::vector<float>& integrals);
// That p_F over the scene's fluorophores on `range`, with F_t their absorbed (c·a) or re-emitted
// spectra. Throws std::invalid_argument if no fluorophore has any of it there.
WavelengthDensity yamamotoFluorophoreDensity(const WavelengthSources& sources, bool absorbed, WavelengthRange range);

class WavelengthStrategy {
 public:
  // Builds `spec` for a site; `material` names the fluorescent material whose event is sampled
  // (sites Fluorescence and Nee). Throws WavelengthStrategyError if the spec does not apply there or its
  // density misses wavelengths the integrand needs (which would bias the estimate).
  WavelengthStrategy(const WavelengthSpec& spec, const WavelengthSources& sources, WavelengthSite site,
                     size_t material = 0);

  // Wavelengths drawn per estimate: one per component for multi-sample MIS, else one.
  int samplesPerEstimate() const;
  struct Draw {
    float lambda = 0.0f;
    float weight = 0.0f;  // MIS weight / density: multiplies the integrand's value at lambda
  };
  // Draw i of samplesPerEstimate().
  Draw draw(int i, float u) const;
  // The one density of a single or "mix" strategy (spec().isDensity()).
  const WavelengthDensity& density() const { return mixture_; }
  const WavelengthSpec& spec() const { return spec_; }

 private:
  WavelengthSpec spec_;
  std::vector<WavelengthDensity> parts_;  // one per component
  std::vector<float> c_;                  // normalised selection weights (one-sample)
  WavelengthDensity mixture_;             // Σ c_k parts_k
};

// Throws WavelengthStrategyError unless `spec` draws from one density (single or mix:), for the
// sites and integrators whose MIS weights need that density.
void requireDensity(const WavelengthSpec& spec, WavelengthSite site, const std::string& where);

}  // namespace kasha
