#pragma once
// Progressive photon mapping for fluorescent scenes (docs/photon-mapping.md), in the probabilistic
// formulation of Knaus & Zwicker 2011: every render pass is one iteration, a photon pass followed
// by one camera sample per pixel, whose estimate uses this iteration's radius r_i only; the film's
// average over samples is their average over iterations.
//
// Photons are light subpaths in Importance mode with their own wavelengths (photon_tracer.h). A
// camera path carries wavelength lanes (hero wavelengths, stratified over the sensor density as in
// the path tracer), passes specular vertices in Radiance mode and at every vertex with a
// non-specular lobe adds the photons within r_i, Σ f·Φ_p / (π r_i² N), N the subpaths of the pass,
// and direct light of the elastic lobe by next-event estimation (lane_next_event.h), so that the
// photons' first vertices count for the fluorescent lobe only and every path is counted by exactly
// one of the two (§3; at the first vertex next-event estimation draws wavelength lanes of its own,
// render/ppm/nee_wavelengths; render/ppm/direct "nee": next-event estimation for every lobe, photons from
// their second vertex on; "photons": no next-event estimation). The
// fluorescent lobe is evaluated exactly from the photon's wavelength to each lane's. The elastic
// lobe needs λ_photon = λ_camera: where the camera path does not depend on its wavelengths (the
// first vertex) the sensor is evaluated at the photon's own wavelength, which is exact; behind
// specular vertices (or always, if asked) an Epanechnikov kernel of half-width h_i = h_1·r_i/r_1
// in wavelength stands in for the delta. Emission seen along the camera path is added exactly.
//
// Media (docs/photon-mapping.md §9): photons and camera paths take the free flights of the light
// tracer and the path tracer; photons at collisions form a volume photon map, and a camera path
// that collides gathers there, Σ f·Φ_p / ((4/3)π r_v,i³ N) with the medium's collision kernel f,
// r_v,i from the three-dimensional schedule, and ends, as at a surface with a non-specular lobe.
#include <optional>

#include "scene/wavelength_strategy.h"
#include "integrators/fluorescence_sampling.h"
#include "integrators/integrator.h"

namespace kasha {

class PpmIntegrator final : public Integrator {
 public:
  // Resolves the derived settings (PhotonMappingSettings) and the lanes (settings.heroWavelengths,
  // kAutoLanes: 4). Throws std::invalid_argument for settings out of range (WavelengthStrategyError
  // for a strategy) and MemoryLimitError if a pass's photons cannot fit the memory limit.
  PpmIntegrator(const Scene& scene, const RenderSettings& settings);
  std::unique_ptr<const PassData> beginPass(const Scene& scene, int firstSample, int count, uint64_t seed,
                                            RayCounter& counter) const override;
  int maxSamplesPerPass() const override { return 1; }
  Vec3 samplePixel(const Scene& scene, Vec2 pixel, Sampler& rng, SampleContext& ctx) const override;
  std::string name() const override { return "ppm"; }
  int lanes() const override { return n_; }

  size_t photonsPerPass() const { return photonsPerPass_; }
  // Gather radius and elastic kernel half-width of the pass that takes sample `sample` (iteration sample + 1).
  float radius(int sample) const;
  // Radius of the volume photons' balls in that pass (the three-dimensional schedule).
  float volumeRadius(int sample) const;
  float bandwidth(int sample) const;

 private:
  // Next-event estimation of the elastic lobe at the first camera vertex with lanes of its own from
  // directLanes_ (uLanes their strata, uLight the light, uPos the point on it): the XYZ it adds.
  Vec3 directElasticOwnLanes(const Scene& scene, const Hit& hit, const Bsdf& bsdf, const Vec3& wo, float uLanes,
                             float uLight, Vec2 uPos, SampleContext& ctx) const;

  WavelengthSources sources_;
  WavelengthStrategy sensor_, light_;
  std::optional<WavelengthDensity> directLanes_;  // own lanes of first-vertex elastic NEE (none: the camera's)
  FluorescenceSampling excitation_;  // λ_i of next-event estimation's fluorescent lobe ("material": the Bsdf's own)
  int n_, maxDepth_, rrDepth_;
  bool hideEmitters_;  // RenderSettings::hideEmitters
  size_t photonsPerPass_;
  float radius1_, volumeRadius1_, alpha_, bandwidth1_;
  bool alwaysKernel_;
  PpmDirectLight direct_;
  int firstStoredDepth_;  // the photon pass stores photons from this vertex of their subpaths on
  uint64_t memoryLimit_;
  SamplerKind sampler_;
  std::vector<Vec3> directXyz_;  // per light: the film's XYZ of its emission seen directly (direct_emission.h)
};

}  // namespace kasha
