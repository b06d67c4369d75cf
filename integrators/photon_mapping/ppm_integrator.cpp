#include "integrators/photon_mapping/ppm_integrator.h"

#include <cmath>
#include <stdexcept>

#include "core/memory_budget.h"
#include "integrators/photon_mapping/photon_map.h"
#include "integrators/photon_mapping/photon_tracer.h"
#include "integrators/progressive_schedule.h"

namespace kasha {
namespace {

// The default r_1 puts this many photons in a disc if a pass's photons spread evenly over all
// surfaces (docs/photon-mapping.md).
constexpr float kPhotonsPerDisc = 16.0f;

struct PhotonPass final : PassData {
  PhotonPass(std::vector<Photon> photons, float r, float h, size_t paths)
      : map(std::move(photons)), radius(r), bandwidth(h), density(1.0f / (kPi * r * r * float(paths))) {}
  PhotonMap map;
  float radius, bandwidth;
  float density;  // 1/(π r² N): turns a sum of f·Φ_p into reflected radiance
};

// The reflected radiance at a camera vertex from the photons of the pass, at λ, the wavelength
// leaving this vertex towards the camera (the camera sample turns it into XYZ with W(λ)/p(λ));
// `bounces` is the number of specular vertices before it. With `exactElastic` (at the first
// vertex) the elastic lobe is instead seen at each photon's own wavelength: those contributions
// go straight to the sensor (sensorResponse) and are added to `photonXyz`.
float gather(const PhotonPass& pass, const Bsdf& bsdf, const Vec3& p, const Vec3& wo, float lambda, int bounces,
             int maxDepth, bool exactElastic, SampleContext& ctx, Vec3& photonXyz) {
  float sum = 0.0f;
  for (const size_t i : pass.map.within(p, pass.radius)) {
    const Photon& ph = pass.map[i];
    if (int(ph.depth) + bounces > maxDepth) continue;
    const Vec3 wi(ph.wi[0], ph.wi[1], ph.wi[2]);  // the photon's direction in its own surface frame
    // Fluorescent lobe: exact for any pair of wavelengths (transport.md §4).
    if (bsdf.has(BsdfFlags::Fluorescent))
      sum += bsdf.eval(TransportMode::Radiance, wi, wo, ph.lambda, lambda, SpectralLobe::Fluorescent) * ph.power;
    const float fe = bsdf.eval(TransportMode::Radiance, wi, wo, ph.lambda, ph.lambda, SpectralLobe::Elastic) * ph.power;
    if (fe <= 0.0f) continue;
    if (exactElastic)
      photonXyz += sensorResponse(ctx, ph.lambda, fe * pass.density);  // the sensor at the photon's own wavelength
    else
      sum += fe * wavelengthKernel(ph.lambda - lambda, pass.bandwidth);
  }
  return sum * pass.density;
}

}  // namespace

PpmIntegrator::PpmIntegrator(const Scene& scene, const RenderSettings& s)
    : sensor_(s.wavelengths.sensor, WavelengthSources(scene), WavelengthSite::Sensor),
      light_(s.wavelengths.light, WavelengthSources(scene), WavelengthSite::LightStart),
      maxDepth_(s.maxDepth), rrDepth_(s.rrDepth), alpha_(s.ppm.alpha),
      alwaysKernel_(s.ppm.alwaysKernel), memoryLimit_(s.memoryLimit), sampler_(s.sampler) {
  requireDensity(s.wavelengths.sensor, WavelengthSite::Sensor, "by ppm");
  requireDensity(s.wavelengths.light, WavelengthSite::LightStart, "by ppm");
  const PhotonMappingSettings& p = s.ppm;
  if (p.photonsPerPass < 0 || !(p.radius >= 0.0f) || !(p.bandwidth >= 0.0f))
    throw std::invalid_argument("ppm: photons per pass, radius and bandwidth must not be negative");
  // Consistency of the elastic kernel (three dimensions: two in space, one in wavelength) needs α > 1/3.
  if (!(p.alpha > 1.0f / 3.0f && p.alpha < 1.0f)) throw std::invalid_argument("ppm: alpha must be in (1/3, 1)");
  // SmallVCM's choice: as many light subpaths per iteration as pixels.
  photonsPerPass_ = p.photonsPerPass > 0 ? size_t(p.photonsPerPass)
                                         : size_t(scene.camera.width()) * size_t(scene.camera.height());
  requireMemory(saturatingMul(photonsPerPass_, kBytesPerPhoton),
                "the photon map of one pass (" + std::to_string(photonsPerPass_) + " photons × " +
                    std::to_string(kBytesPerPhoton) + " bytes; lower render/ppm/photons_per_pass)",
                memoryLimit_);
  double area = 0.0;
  for (const Shape& shape : scene.shapes) area += shape.area;
  radius1_ = p.radius > 0.0f ? p.radius : float(std::sqrt(kPhotonsPerDisc * area / (kPi * double(photonsPerPass_))));
  bandwidth1_ = p.bandwidth > 0.0f ? p.bandwidth : 0.01f * (scene.range.max - scene.range.min);
}

float PpmIntegrator::radius(int sample) const { return std::sqrt(progressiveRadiusSquared(radius1_, alpha_, sample + 1)); }

float PpmIntegrator::bandwidth(int sample) const { return bandwidth1_ * radius(sample) / radius1_; }

std::unique_ptr<const PassData> PpmIntegrator::beginPass(const Scene& scene, int firstSample, int, uint64_t seed,
                                                         RayCounter& counter) const {
  std::vector<Photon> photons;
  if (maxDepth_ > 0) {
    PhotonTracing t;
    t.paths = photonsPerPass_;
    t.maxDepth = maxDepth_;
    t.rrDepth = rrDepth_;
    t.memoryLimit = memoryLimit_;
    t.sampler = sampler_;
    t.wavelengths = &light_.density();
    // A stream family per iteration, apart from the camera samples' (render_loop.cpp).
    const uint64_t passSeed = mixBits(mixBits(seed ^ 0x5851f42d4c957f2dULL) + uint64_t(firstSample));
    photons = tracePhotons(scene, t, passSeed, counter);
  }
  return std::make_unique<PhotonPass>(std::move(photons), radius(firstSample), bandwidth(firstSample), photonsPerPass_);
}

Vec3 PpmIntegrator::samplePixel(const Scene& scene, Vec2 pixel, Sampler& rng, SampleContext& ctx) const {
  const auto& pass = static_cast<const PhotonPass&>(*ctx.pass);
  const WavelengthSample ws = sensor_.density().sample(rng.uniform());
  if (ws.pdf <= 0.0f) return Vec3(0.0f);
  Ray ray = scene.camera.generateRay(pixel + rng.uniform2());
  float lambda = ws.lambda, beta = 1.0f;  // beta: throughput of the specular vertices so far
  float L = 0.0f;    // radiance arriving at the camera's wavelength
  Vec3 xyz(0.0f);    // elastic photons seen at their own wavelengths
  for (int bounces = 0;; ++bounces) {
    const std::optional<Hit> hit = scene.accel->intersect(ray);
    ++ctx.counter.closest;
    if (!hit) {
      if (const EnvironmentLight* env = scene.environment()) L += beta * env->Le(lambda, ray.d);
      break;
    }
    const Shape& shape = scene.shapes[hit->shape];
    if (shape.emission) L += beta * shape.emission->eval(lambda, hit->ng, -ray.d);
    if (bounces >= maxDepth_) break;
    const Bsdf bsdf = scene.bsdf(*hit, {&lambda, 1});
    const Vec3 wo = bsdf.toLocal(-ray.d);
    if (!bsdf.has(BsdfFlags::DeltaDirection))
      L += beta * gather(pass, bsdf, hit->p, wo, lambda, bounces, maxDepth_, bounces == 0 && !alwaysKernel_, ctx, xyz);
    // The gather covers every non-specular lobe; a sampled specular lobe continues the path.
    const std::optional<ScatterSample> ss =
        bsdf.sample(TransportMode::Radiance, wo, lambda, rng.uniform3());
    if (!ss || !ss->specular) break;
    beta *= ss->f * std::abs(ss->w.z) / ss->pdf;
    if (!(beta > 0.0f)) break;
    lambda = ss->lambda;
    const Vec3 w = bsdf.toWorld(ss->w);
    ray = Ray{offsetPoint(hit->p, hit->ng, w), w};
  }
  // W(λ)/p(λ) at the camera sample's wavelength (transport.md §1).
  return xyz + sensorResponse(ctx, ws.lambda, L / ws.pdf);
}

}  // namespace kasha
