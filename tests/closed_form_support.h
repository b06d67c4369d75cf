#pragma once
// The batch-statistics check of a render's mean XYZ against the closed forms of docs/validation.md §1–2
// (tests/spectral_quadrature.h): shared by the per-integrator closed-form tests and the
// per-wavelength-strategy ones.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "scene/scene_loader.h"
#include "integrators/integrator_factory.h"
#include "tests/integrator_names.h"
#include "integrators/render_loop.h"
#include "tests/spectral_quadrature.h"
#include "tests/support.h"

namespace kasha::test {

inline const JungBbrrdf& jung(const Scene& s) {
  const auto* m = dynamic_cast<const JungBbrrdf*>(s.materials.at(0).get());
  EXPECT_NE(m, nullptr);
  return *m;
}

// The mean image XYZ of each of `batches` independent renders (seeds firstSeed, firstSeed + 1, …).
inline std::vector<DVec3> batchMeans(const Scene& scene, const Integrator& integrator, int batches, int spp,
                                     uint64_t firstSeed, SamplerKind sampler = SamplerKind::Sobol) {
  std::vector<DVec3> means;
  for (int b = 0; b < batches; ++b) {
    Film film(scene.camera.width(), scene.camera.height());
    RenderOptions opt;
    opt.spp = spp;
    opt.seed = firstSeed + uint64_t(b);
    opt.sampler = sampler;
    render(scene, integrator, film, opt);
    means.push_back(film.meanXyz());
  }
  return means;
}

// Mean image XYZ over `batches` independent renders (seeds 1000, 1001, …) of `integrator` with
// `settings`; checks each channel within 4 standard errors of `exact`, and that the test has power.
inline void expectXyzAgreement(Scene& scene, const std::string& integrator, const RenderSettings& settings,
                               const Vec3& exact, int batches, int spp) {
  const std::unique_ptr<Integrator> in = makeTestIntegrator(integrator, scene, settings);
  std::vector<double> bx, by, bz;
  for (const DVec3& m : batchMeans(scene, *in, batches, spp, 1000, settings.sampler))
    bx.push_back(m.x), by.push_back(m.y), bz.push_back(m.z);
  const BatchStats s[3] = {batchStats(bx), batchStats(by), batchStats(bz)};
  for (int c = 0; c < 3; ++c) {
    SCOPED_TRACE("channel " + std::string(1, "XYZ"[c]) + " depth " + std::to_string(settings.maxDepth));
    // The test must have power: the standard error is small against the value (or, for values
    // near zero such as the direct view of a UV emitter, small in absolute terms: scenes are O(1)).
    EXPECT_LT(s[c].stderr_, 0.03 * std::abs(exact[c]) + 1e-4);
    // The 1e-4 relative term covers the quadrature of `exact` and a residual bias the scrambled
    // Sobol sampler resolves: pt's sphere furnace loses 3e-5 of each bounce's contribution
    // (measured with the path's dimensions drawn by PCG32 as well; cause open, docs/sampler.md).
    EXPECT_NEAR(s[c].mean, exact[c], 4.0 * s[c].stderr_ + 1e-4 * std::abs(exact[c]))
        << "mean " << s[c].mean << " ± " << s[c].stderr_ << ", exact " << exact[c];
  }
}

inline std::unique_ptr<Scene> load(const std::string& name) { return loadScene(sourcePath("scenes/validation/" + name)); }

inline Fn emissionOf(const Scene& s) {
  const AreaEmission& e = *s.shapes.at(0).emission;
  return [e](double l) { return double(e.scale * e.radiance(float(l))); };
}

}  // namespace kasha::test
