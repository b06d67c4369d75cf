// Spectral bins of the path tracer with wavelength lanes: each lane's throughput is kept per sensor
// wavelength (integrators/sensor_shares.h), so that every share reaches the bin of the wavelength
// the sensor sees, also after a fluorescent event has mixed the lanes. On the fluorescent Cornell
// box (a fluorescent sphere, a directly seen light) at 24×24, uniform sensor wavelengths:
// - the image's mean spectrum with 4 lanes agrees with one wavelength per path, bin by bin, within
//   4 standard errors of 12 batches (with lanes through and ended at fluorescent events);
// - the bins integrate to the XYZ layer the same samples gave (1 nm bins: only the observer's
//   variation inside a bin separates them).
#include <gtest/gtest.h>

#include "core/color.h"
#include "core/film.h"
#include "integrators/integrator_factory.h"
#include "integrators/render_loop.h"
#include "scene/scene_loader.h"
#include "tests/region_batches.h"
#include "tests/support.h"

namespace kasha {
namespace {

constexpr int kRes = 24, kBatches = 12, kGroup = 47;  // 1 nm bins, compared in groups of 47 nm

struct Batches {
  std::vector<std::vector<double>> groups;  // [group][batch]: the image's mean radiance per nm
  std::vector<double> yFromBins, y;         // per batch: Y integrated from the bins, and the film's
};

Batches render(const Scene& scene, const RenderSettings& settings, int spp) {
  const std::unique_ptr<Integrator> integrator = makeIntegrator("pt", scene, settings);
  const SpectralBins bins = SpectralBins::fromStep(scene.range, 1.0f);
  // ∫ over each bin of the film's Y weight ȳ/∫ȳ (midpoint rule on 0.01 nm).
  std::vector<double> yWeight(size_t(bins.count), 0.0);
  for (int b = 0; b < bins.count; ++b)
    for (int i = 0; i < 100; ++i) yWeight[size_t(b)] += 0.01 * Observer::cie1931().weight(bins.lower(b) + 0.01f * (float(i) + 0.5f)).y;
  Batches out;
  out.groups.resize(size_t(bins.count / kGroup));
  for (int k = 0; k < kBatches; ++k) {
    Film film(kRes, kRes);
    SpectralFilm spectral(kRes, kRes, bins);
    RenderOptions opt;
    opt.spp = spp;
    opt.seed = 5000 + uint64_t(k);
    opt.spectral = &spectral;
    kasha::render(scene, *integrator, film, opt);
    std::vector<double> mean(size_t(bins.count), 0.0);
    for (int y = 0; y < kRes; ++y)
      for (int x = 0; x < kRes; ++x)
        for (int b = 0; b < bins.count; ++b) mean[size_t(b)] += spectral.value(x, y, b) / double(kRes * kRes);
    double yFromBins = 0.0;
    for (int b = 0; b < bins.count; ++b) yFromBins += mean[size_t(b)] * yWeight[size_t(b)];
    out.yFromBins.push_back(yFromBins);
    out.y.push_back(film.meanXyz().y);
    for (size_t g = 0; g < out.groups.size(); ++g) {
      double sum = 0.0;
      for (int b = 0; b < kGroup; ++b) sum += mean[g * kGroup + size_t(b)] / kGroup;
      out.groups[g].push_back(sum);
    }
  }
  return out;
}

class HeroSpectralBins : public ::testing::TestWithParam<FluorescentLanes> {};

TEST_P(HeroSpectralBins, AgreeWithOneWavelengthAndIntegrateToY) {
  auto scene = loadScene(test::sourcePath("scenes/cornell_fluorescent.json"));
  test::useSquareCamera(*scene, kRes);
  RenderSettings settings = scene->render;
  settings.maxDepth = 8;
  // Uniform sensor wavelengths: every bin gets its share of samples (cmf leaves the red end thin).
  settings.wavelengths.sensor = parseWavelengthSpec("uniform");
  settings.heroWavelengths = 1;
  const Batches one = render(*scene, settings, 256);
  settings.heroWavelengths = 4;
  settings.fluorescentLanes = GetParam();
  const Batches lanes = render(*scene, settings, 128);
  ASSERT_EQ(lanes.groups.size(), 10u);
  for (size_t g = 0; g < lanes.groups.size(); ++g) {
    SCOPED_TRACE("bins " + std::to_string(360 + kGroup * int(g)) + "-" + std::to_string(360 + kGroup * int(g + 1)) + " nm");
    const test::BatchStats a = test::batchStats(one.groups[g]), b = test::batchStats(lanes.groups[g]);
    const double se = std::hypot(a.stderr_, b.stderr_);
    EXPECT_LT(se, 0.05 * a.mean + 1e-3);  // power: the scene's radiance is O(1) in its visible bins
    EXPECT_NEAR(b.mean, a.mean, 4.0 * se) << "one wavelength " << a.mean << " ± " << a.stderr_ << ", lanes " << b.mean
                                          << " ± " << b.stderr_;
  }
  // Each sample adds W(λ)·v to the XYZ film and v/Δ to λ's bin; over the image and 1 nm bins the
  // observer's variation inside a bin averages out (the Python test bounds it pixel by pixel).
  for (int k = 0; k < kBatches; ++k) EXPECT_NEAR(lanes.yFromBins[size_t(k)], lanes.y[size_t(k)], 0.005 * lanes.y[size_t(k)]);
}

INSTANTIATE_TEST_SUITE_P(FluorescentLanes, HeroSpectralBins,
                         ::testing::Values(FluorescentLanes::Through, FluorescentLanes::End),
                         [](const auto& info) { return std::string(toString(info.param)); });

}  // namespace
}  // namespace kasha
