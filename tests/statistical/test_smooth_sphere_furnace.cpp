// Shading normals (Veach 1997 §5.3) on a coarse smooth-shaded OBJ sphere (scenes/validation/
// smooth_sphere.obj: radial vertex normals up to 21° off the flat faces' normals).
//
// Closed forms. With Veach's shading-normal BSDF (Veach 1997 §5.3; materials/shading_normal.h)
//   f_s(ω_i → ω_o) = f(ω_i → ω_o)·|ω_i·n_s| / |ω_i·n_g|,
// zero unless ω_i and ω_o each lie on the same side of n_s as of n_g (no light leaks), a
// Lambertian point of reflectance ρ seen along ω_o (with ω_o·n_s > 0) reflects
//  - under a uniform environment L: ρ·L·∫ (ω_i·n_s)⁺ dω_i/π over ω_i·n_g > 0 = ρ·L·(1 + cos α)/2,
//    α the angle between n_s and n_g (the clamped cosine lobe about n_s cut by the plane of n_g:
//    the sky view factor of a tilted plane): the white furnace, smooth_sphere_environment.json;
//  - under a distant light of irradiance E from ω_i: ρ·E·(ω_i·n_s)⁺/π where ω_i·n_g > 0:
//    smooth_sphere_distant.json.
// The sphere is convex, so no light reaches it twice. The tests take these over each pixel by
// tracing camera rays on a fine stratified grid and check the renders region by region within 4
// standard errors: path tracing (Radiance mode) in the furnace, path and light tracing (Importance
// mode, where f_s is the non-symmetric adjoint) under the distant light, and photon mapping there
// (photons carry flux through the surface, so the gather applies |ω_i·n_s|/|ω_i·n_g| itself).
#include <gtest/gtest.h>

#include <functional>

#include "core/color.h"
#include "integrators/integrator_factory.h"
#include "scene/scene_loader.h"
#include "tests/region_batches.h"

namespace kasha {
namespace {

using test::BatchStats;

// The 16×16 images in 4×4 blocks of 4×4 pixels.
int regionOf(int x, int y) { return (y / 4) * 4 + x / 4; }
constexpr int kRegions = 16;

// What a point reflects towards the camera (per unit of the light's constant spectrum), given the
// view direction ω_o and the shading and geometric normals (the same for flat shading).
using PointValue = std::function<double(const Vec3& wo, const Vec3& ns, const Vec3& ng)>;

// Which region a pixel belongs to, and how many there are.
struct Regions {
  std::function<int(int x, int y)> of = regionOf;
  int count = kRegions;
};

// Σ over each region's pixels of the pixel's mean point value, by n×n stratified camera rays per
// pixel; a ray that misses the sphere sees `miss` (the environment's radiance, or 0).
std::vector<double> expectedRegions(const Scene& scene, int n, const PointValue& value, double miss,
                                    const Regions& regions = {}) {
  std::vector<double> sum(size_t(regions.count), 0.0);
  const Camera& cam = scene.camera;
  for (int y = 0; y < cam.height(); ++y)
    for (int x = 0; x < cam.width(); ++x) {
      double pixel = 0.0;
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const Ray ray = cam.generateRay(Vec2(float(x) + (float(i) + 0.5f) / float(n), float(y) + (float(j) + 0.5f) / float(n)), Vec2(0.5f));
          const std::optional<Hit> h = scene.accel->intersect(ray);
          if (!h) {
            pixel += miss;
            continue;
          }
          const Vec3 ns = scene.shapes[h->shape].shadingNormal(h->prim, h->bary, h->ng);
          pixel += value(-ray.d, ns, h->ng);
        }
      sum[size_t(regions.of(x, y))] += pixel / double(n * n);
    }
  return sum;
}

// Renders with each integrator in batches and compares every region's X, Y, Z with the closed
// form; `flat` is the closed form with the geometric normal in place of the shading normal, from
// which some region's Y must differ by 8 standard errors (the test sees shading normals).
void expectRegions(const Scene& scene, const std::vector<std::string>& integrators, const std::vector<double>& exact,
                   const std::vector<double>& flat, int spp, int batches, const Regions& regions = {}) {
  const Observer& o = Observer::cie1931();  // XYZ of a constant spectrum of 1: Y = 1
  const Vec3 white(o.xbar.integral(360, 830) / o.yIntegral, 1.0f, o.zbar.integral(360, 830) / o.yIntegral);
  for (const std::string& name : integrators) {
    SCOPED_TRACE(name);
    const std::unique_ptr<Integrator> integrator = makeIntegrator(name, scene, scene.render);
    const std::vector<BatchStats> s =
        test::regionBatches(scene, *integrator, 16, 16, regions.count, regions.of, spp, batches, 7919);
    double separation = 0.0;  // the largest |flat − exact| in Y, in standard errors
    for (int r = 0; r < regions.count; ++r)
      for (int c = 0; c < 3; ++c) {
        const BatchStats& b = s[size_t(r * 3 + c)];
        const double e = exact[size_t(r)] * double(white[c]);
        SCOPED_TRACE("region " + std::to_string(r) + " channel " + std::string(1, "XYZ"[c]));
        EXPECT_LT(b.stderr_, 0.03 * e + 1e-3) << "the test has power";
        EXPECT_NEAR(b.mean, e, 4.0 * b.stderr_ + 2e-4 * e) << "mean " << b.mean << " ± " << b.stderr_;
        if (c == 1) separation = std::max(separation, std::abs(flat[size_t(r)] - e) / b.stderr_);
      }
    EXPECT_GT(separation, 8.0) << "flat shading would pass too";
  }
}

const Vec3 kDistantTravel = glm::normalize(Vec3(0.4f, -0.5f, 1.0f));  // smooth_sphere_distant.json

// Nothing reaches the camera from a point it sees below the shading normal's horizon.
bool visible(const Vec3& wo, const Vec3& ns) { return glm::dot(wo, ns) > 0.0f; }

double distantValue(const Vec3& wi, const Vec3& wo, const Vec3& n, const Vec3& ng) {
  if (!visible(wo, n) || glm::dot(wi, ng) <= 0.0f) return 0.0;
  return 0.8 * std::max(0.0, double(glm::dot(wi, n))) / double(kPi);
}

TEST(SmoothSphere, WhiteFurnacePathTracing) {
  const auto scene = loadScene(test::sourcePath("scenes/validation/smooth_sphere_environment.json"));
  const auto furnace = [](const Vec3& wo, const Vec3& ns, const Vec3& ng) {
    return visible(wo, ns) ? 0.5 * (1.0 + double(glm::dot(ns, ng))) : 0.0;
  };
  const auto flat = [](const Vec3&, const Vec3&, const Vec3&) { return 1.0; };
  expectRegions(*scene, {"pt"}, expectedRegions(*scene, 32, furnace, 1.0), expectedRegions(*scene, 32, flat, 1.0), 512, 12);
}

TEST(SmoothSphere, PathAndLightTracingUnderADistantLight) {
  const auto scene = loadScene(test::sourcePath("scenes/validation/smooth_sphere_distant.json"));
  const Vec3 wi = -kDistantTravel;
  const auto shaded = [&](const Vec3& wo, const Vec3& ns, const Vec3& ng) { return distantValue(wi, wo, ns, ng); };
  const auto flat = [&](const Vec3& wo, const Vec3&, const Vec3& ng) { return distantValue(wi, wo, ng, ng); };
  expectRegions(*scene, {"pt", "lt"}, expectedRegions(*scene, 32, shaded, 0.0), expectedRegions(*scene, 32, flat, 0.0), 512, 24);
}

// Photons bring flux through the surface, so photon mapping's gather must apply f_s's factor
// |ω_i·n_s|/|ω_i·n_g| itself. Over the 4×4 regions that factor averages out across each face, so
// the pixels are split by the sign of its effect: where the closed form lies above the estimate
// without it (f·(ω_i·n_g) with the same visibility), where below, and the background; a gather
// without the factor is more than 8σ off. The default first radius (16 photons per disc at one
// photon per pixel) would blur the shading over half the sphere: a small radius and many photons
// per pass keep the kernel's bias below the noise.
TEST(SmoothSphere, PhotonMappingUnderADistantLight) {
  const auto scene = loadScene(test::sourcePath("scenes/validation/smooth_sphere_distant.json"));
  scene->render.ppm.photonsPerPass = 8192;
  scene->render.ppm.radius = 0.05f;
  const Vec3 wi = -kDistantTravel;
  const auto shaded = [&](const Vec3& wo, const Vec3& ns, const Vec3& ng) { return distantValue(wi, wo, ns, ng); };
  const auto unfactored = [&](const Vec3& wo, const Vec3& ns, const Vec3& ng) {
    const bool lit = glm::dot(wi, ns) > 0.0f && glm::dot(wi, ng) > 0.0f;
    return visible(wo, ns) && lit ? 0.8 * double(glm::dot(wi, ng)) / double(kPi) : 0.0;
  };
  const Regions pixels{[](int x, int y) { return y * 16 + x; }, 256};
  const std::vector<double> a = expectedRegions(*scene, 32, shaded, 0.0, pixels);
  const std::vector<double> b = expectedRegions(*scene, 32, unfactored, 0.0, pixels);
  const Regions bySign{[&](int x, int y) {
                         const size_t i = size_t(y * 16 + x);
                         return a[i] == b[i] ? 2 : a[i] > b[i] ? 0 : 1;
                       },
                       3};
  expectRegions(*scene, {"ppm"}, expectedRegions(*scene, 32, shaded, 0.0, bySign),
                expectedRegions(*scene, 32, unfactored, 0.0, bySign), 128, 16, bySign);
}

}  // namespace
}  // namespace kasha
