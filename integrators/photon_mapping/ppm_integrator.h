#pragma once
// Progressive photon mapping for fluorescent scenes (docs/photon-mapping.md), in the probabilistic
// formulation of Knaus & Zwicker 2011: every render pass is one iteration, a photon pass followed
// by one camera sample per pixel, whose estimate uses this iteration's radius r_i only; the film's
// average over samples is their average over iterations.
//
// Photons are light subpaths in Importance mode with their own wavelengths (photon_tracer.h). A
// camera path passes specular vertices in Radiance mode and gathers at every vertex with a
// non-specular lobe: Σ f·Φ_p / (π r_i² N) over the photons within r_i, N the subpaths of the pass.
// The fluorescent lobe is evaluated exactly from the photon's wavelength to the camera's. The
// elastic lobe needs λ_photon = λ_camera: where the camera path does not depend on its wavelength
// (the first vertex) the sensor is evaluated at the photon's own wavelength, which is exact;
// behind specular vertices (or always, if asked) an Epanechnikov kernel of half-width h_i =
// h_1·r_i/r_1 in wavelength stands in for the delta. Emission seen along the camera path is added
// exactly; there is no next-event estimation.
#include "scene/wavelength_strategy.h"
#include "integrators/integrator.h"

namespace kasha {

class PpmIntegrator final : public Integrator {
 public:
  // Resolves the derived settings (PhotonMappingSettings). Throws std::invalid_argument for
  // settings out of range and MemoryLimitError if a pass's photons cannot fit the memory limit.
  PpmIntegrator(const Scene& scene, const RenderSettings& settings);
  std::unique_ptr<const PassData> beginPass(const Scene& scene, int firstSample, int count, uint64_t seed,
                                            RayCounter& counter) const override;
  int maxSamplesPerPass() const override { return 1; }
  Vec3 samplePixel(const Scene& scene, Vec2 pixel, Sampler& rng, SampleContext& ctx) const override;
  std::string name() const override { return "ppm"; }

  size_t photonsPerPass() const { return photonsPerPass_; }
  // Gather radius and elastic kernel half-width of the pass that takes sample `sample` (iteration sample + 1).
  float radius(int sample) const;
  float bandwidth(int sample) const;

 private:
  WavelengthStrategy sensor_, light_;
  int maxDepth_, rrDepth_;
  size_t photonsPerPass_;
  float radius1_, alpha_, bandwidth1_;
  bool alwaysKernel_;
  uint64_t memoryLimit_;
  SamplerKind sampler_;
};

}  // namespace kasha
