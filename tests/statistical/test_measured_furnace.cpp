// Closed-form furnaces (docs/validation.md §1) for the measured materials: a sphere of the pink Post-it
// material, emitting L_e = 1 on both sides, seen from its centre. Every direction then carries
// the same radiance, the solution of L = L_e + T·L with, for the measured matrix,
//   (T·L)(λ_o) = d(λ_o)·L(λ_o) + ∫ F(λ_o; λ_i)·L(λ_i) dλ_i,
// and for its Zhdanov fit without gloss (Zhdanov eqs. 2–3)
//   (T·L)(λ_o) = p(λ_o)·L(λ_o) + E(λ_o)·∫ A(λ_i)·L(λ_i) dλ_i.
// The Neumann series is summed on a 1 nm grid with the material's own functions (exact midpoint
// quadrature: they are linear between the 10 nm knots), and every integrator must agree with it
// within its standard error.
#include <gtest/gtest.h>

#include <functional>
#include <map>

#include "core/color.h"
#include "scene/scene_loader.h"
#include "integrators/integrator_factory.h"
#include "materials/measured_reradiation.h"
#include "materials/zhdanov_bdf.h"
#include "tests/region_batches.h"
#include "tests/support.h"

namespace kasha {
namespace {

using Transport = std::function<std::vector<double>(const std::vector<double>& grid, const std::vector<double>& L)>;

// L = Σ_k T^k L_e on the grid, in XYZ.
Vec3 furnaceXyz(const std::vector<double>& grid, const Transport& T) {
  std::vector<double> term(grid.size(), 1.0), sum = term;
  for (int k = 0; k < 400; ++k) {
    term = T(grid, term);
    for (size_t i = 0; i < sum.size(); ++i) sum[i] += term[i];
  }
  // The film's XYZ: ∫ (x̄, ȳ, z̄)·L dλ / ∫ ȳ dλ (a constant radiance 1 has Y = 1).
  const Observer& o = Observer::cie1931();
  Vec3 xyz(0.0f);
  double yIntegral = 0.0;
  for (size_t i = 0; i < grid.size(); ++i) {
    const float l = float(grid[i]);
    xyz += Vec3(o.xbar(l), o.ybar(l), o.zbar(l)) * float(sum[i]);  // 1 nm cells
    yIntegral += o.ybar(l);
  }
  return xyz / float(yIntegral);
}

void expectFurnace(const std::string& file, const Transport& T) {
  auto scene = loadScene(test::sourcePath("scenes/validation/" + file));
  std::vector<double> grid;
  for (double l = scene->range.min + 0.5; l < scene->range.max; l += 1.0) grid.push_back(l);
  const Vec3 exact = furnaceXyz(grid, T);
  for (const char* name : {"pt", "lt", "bdpt-shared", "bdpt-independent"}) {
    SCOPED_TRACE(name);
    RenderSettings settings = scene->render;
    settings.maxDepth = 1000;
    settings.rrDepth = 3;
    const std::unique_ptr<Integrator> integrator = makeIntegrator(name, *scene, settings);
    const std::vector<test::BatchStats> s = test::regionBatches(
        *scene, *integrator, scene->camera.width(), scene->camera.height(), 1, [](int, int) { return 0; }, 128, 16, 17);
    const double pixels = double(scene->camera.width()) * scene->camera.height();
    for (int c = 0; c < 3; ++c) {
      const double mean = s[size_t(c)].mean / pixels, err = s[size_t(c)].stderr_ / pixels;
      EXPECT_LT(err, 0.05 * exact[c]) << "XYZ"[c];
      EXPECT_NEAR(mean, exact[c], 4.0 * err + 1e-5 * exact[c]) << "XYZ"[c] << ": " << mean << " ± " << err;
    }
  }
}

const Material& wall(const std::string& file) {
  static std::map<std::string, std::unique_ptr<Scene>> scenes;
  auto& s = scenes[file];
  if (!s) s = loadScene(test::sourcePath("scenes/validation/" + file));
  return *s->materials.at(0);
}

TEST(MeasuredFurnace, PinkPostItMatrixSlow) {
  const auto& m = dynamic_cast<const MeasuredReradiation&>(wall("furnace_postit_measured.json"));
  expectFurnace("furnace_postit_measured.json", [&](const std::vector<double>& g, const std::vector<double>& L) {
    std::vector<double> out(g.size());
    for (size_t o = 0; o < g.size(); ++o) {
      double sum = m.diagonal(float(g[o])) * L[o];
      for (size_t i = 0; i < g.size(); ++i) sum += m.F(float(g[o]), float(g[i])) * L[i];
      out[o] = sum;
    }
    return out;
  });
}

TEST(MeasuredFurnace, PinkPostItZhdanovFitSlow) {
  const auto& m = dynamic_cast<const ZhdanovBdf&>(wall("furnace_postit_zhdanov.json"));
  ASSERT_EQ(m.gloss(), 0.0f);
  expectFurnace("furnace_postit_zhdanov.json", [&](const std::vector<double>& g, const std::vector<double>& L) {
    double absorbed = 0.0;
    for (size_t i = 0; i < g.size(); ++i) absorbed += m.A(float(g[i])) * L[i];
    std::vector<double> out(g.size());
    for (size_t o = 0; o < g.size(); ++o) out[o] = m.passive(float(g[o])) * L[o] + m.E(float(g[o])) * absorbed;
    return out;
  });
}

}  // namespace
}  // namespace kasha
