#include "integrators/photon_mapping/ppm_integrator.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/memory_budget.h"
#include "integrators/direct_emission.h"
#include "integrators/integrator_factory.h"
#include "integrators/lane_next_event.h"
#include "integrators/medium_transport.h"
#include "integrators/photon_mapping/direct_light_wavelengths.h"
#include "integrators/photon_mapping/photon_gather.h"
#include "integrators/photon_mapping/photon_tracer.h"
#include "integrators/progressive_schedule.h"

namespace kasha {
namespace {

// The default r_1 puts this many photons in a disc if a pass's photons spread evenly over all
// surfaces (docs/photon-mapping.md).
constexpr float kPhotonsPerDisc = 16.0f;
// The default r_v,1 as a share of r_1: media are often a few r_1 thick (a cuvette, a glass, a
// slab), and a ball reaching out of its medium finds no photons there; on the three media scenes
// r_1 left the glow 5–19% dark, a quarter of it 0–6% (docs/photon-mapping.md §9).
constexpr float kVolumeRadiusShare = 0.25f;

// The elastic lobe for every lane, chosen with probability 1: each keeps its wavelength.
LaneEvent elasticEvent(std::span<const float> known) {
  LaneEvent e;
  e.n = int(known.size());
  for (int j = 0; j < e.n; ++j) {
    e.lambda[j] = known[j];
    e.source[j] = j;
    e.scale[j] = 1.0f;
  }
  return e;
}

// Lane j at the stratum (u + j/n) of p's inverse CDF, weighted by 1/(n·p(λ_j)) in its own sensor
// share (Wilkie14 eq. 8, as the path tracer's lanes).
CameraLanes stratifiedLanes(const WavelengthDensity& p, float u, int n) {
  const SampledLanes sampled = sampleLanes(p, u, n);
  CameraLanes lanes;
  lanes.n = n;
  for (int j = 0; j < n; ++j) {
    lanes.lambda[j] = sampled.lambda[j];
    lanes.beta[j].v[j] = sampled.pdf[j] > 0.0f ? 1.0f / (float(n) * sampled.pdf[j]) : 0.0f;
  }
  return lanes;
}

// Next-event estimation for event `direct` of `lanes` (known: their wavelengths before it), its
// light chosen after the lanes' importance (lane_light_choice.h), weight 1: no other estimator
// counts these paths (§3).
SensorShares lanesNextEvent(const Scene& scene, const Hit& hit, VertexMedium where, const Bsdf& bsdf, const Vec3& wo,
                            const CameraLanes& lanes, const LaneEvent& direct, float uLight, Vec2 uPos, RayCounter& counter) {
  const std::span<const float> known(lanes.lambda, size_t(lanes.n));
  thread_local LaneLightChoice lights;
  float before[kMaxLanes], importance[kMaxLanes];
  for (int j = 0; j < lanes.n; ++j) before[j] = magnitude(lanes.beta[j]);
  laneImportance(bsdf, TransportMode::Radiance, known, before, direct, importance);
  lights.reset(scene, {direct.lambda, size_t(direct.n)}, importance);
  return laneNextEvent(scene, hit, where, bsdf, wo, known, lanes.beta, direct, lights, /*lambdaOut0, unused without MIS*/ 0.0f,
                       uLight, uPos, NeeWeight::Alone, counter);
}

}  // namespace

PpmIntegrator::PpmIntegrator(const Scene& scene, const RenderSettings& s)
    : sources_(scene),
      sensor_(s.wavelengths.sensor, sources_, WavelengthSite::Sensor),
      light_(s.wavelengths.light, sources_, WavelengthSite::LightStart),
      directLanes_(directLightWavelengths(sources_, s.ppm.neeWavelengths)),
      excitation_(s.wavelengths.fluorescence, sources_, scene.materials.size()),
      n_(s.heroWavelengths == kAutoLanes ? kDefaultLanes : s.heroWavelengths),
      maxDepth_(s.maxDepth), rrDepth_(s.rrDepth), hideEmitters_(s.hideEmitters), alpha_(s.ppm.alpha),
      alwaysKernel_(s.ppm.alwaysKernel), direct_(s.ppm.direct), memoryLimit_(s.memoryLimit),
      sampler_(s.sampler), directXyz_(directEmissionXyz(scene)) {
  requireDensity(s.wavelengths.sensor, WavelengthSite::Sensor, "by ppm");
  requireDensity(s.wavelengths.light, WavelengthSite::LightStart, "by ppm");
  requireLaneSettings(s, n_, 1, "ppm");
  // The excitation strategy serves next-event estimation's fluorescent lobe, which only "nee" has.
  if (direct_ != PpmDirectLight::Nee && !s.wavelengths.fluorescence.uses(WavelengthSpec::Kind::Material))
    throw WavelengthStrategyError(WavelengthSite::Fluorescence,
                                  "fluorescence_sampling '" + s.wavelengths.fluorescence.text +
                                      "' applies to ppm only with render/ppm/direct \"nee\" (leave it at 'material')");
  const PhotonMappingSettings& p = s.ppm;
  checkProgressiveSettings(p, [](const char* key, const std::string& why) {
    throw std::invalid_argument(std::string("ppm: render/ppm/") + key + " " + why);
  });
  // SmallVCM's choice: as many light subpaths per iteration as pixels.
  photonsPerPass_ = p.photonsPerPass > 0 ? size_t(p.photonsPerPass)
                                         : size_t(scene.camera.width()) * size_t(scene.camera.height());
  // At least one vertex of every subpath, its lanes in photonsPerVertex photons.
  const size_t minPhotons = saturatingMul(photonsPerPass_, photonsPerVertex(n_));
  requireMemory(saturatingMul(minPhotons, kBytesPerPhoton),
                "the photon map of one pass (" + std::to_string(minPhotons) + " photons × " +
                    std::to_string(kBytesPerPhoton) + " bytes; lower render/ppm/photons_per_pass or the lanes)",
                memoryLimit_);
  double area = 0.0;
  for (const Shape& shape : scene.shapes) area += shape.area;
  radius1_ = p.radius > 0.0f ? p.radius : float(std::sqrt(kPhotonsPerDisc * area / (kPi * double(photonsPerPass_))));
  volumeRadius1_ = p.volumeRadius > 0.0f ? p.volumeRadius : kVolumeRadiusShare * radius1_;
  // A photon's first vertex is light straight from a light: needed unless next-event estimation
  // counts it for every lobe, or it serves only fluorescent lobes and the scene has none (on
  // surfaces or in media).
  const bool fluoresces = !sources_.fluorophores.empty() || scene.hasFluorescentMedia();
  firstStoredDepth_ = direct_ == PpmDirectLight::Nee || (direct_ == PpmDirectLight::NeeElastic && !fluoresces) ? 2 : 1;
  bandwidth1_ = p.bandwidth > 0.0f ? p.bandwidth : 0.01f * (scene.range.max - scene.range.min);
}

float PpmIntegrator::radius(int sample) const { return progressiveRadius(radius1_, alpha_, sample + 1, 2); }

float PpmIntegrator::volumeRadius(int sample) const { return progressiveRadius(volumeRadius1_, alpha_, sample + 1, 3); }

float PpmIntegrator::bandwidth(int sample) const { return bandwidth1_ * radius(sample) / radius1_; }

std::unique_ptr<const PassData> PpmIntegrator::beginPass(const Scene& scene, int firstSample, int, uint64_t seed,
                                                         RayCounter& counter) const {
  PassPhotons photons;
  if (maxDepth_ > 0) {
    PhotonTracing t;
    t.paths = photonsPerPass_;
    t.lanes = n_;
    t.maxDepth = maxDepth_;
    t.rrDepth = rrDepth_;
    t.firstStoredDepth = firstStoredDepth_;
    t.memoryLimit = memoryLimit_;
    t.sampler = sampler_;
    t.wavelengths = &light_.density();
    // A stream family per iteration, apart from the camera samples' (render_loop.cpp).
    const uint64_t passSeed = mixBits(mixBits(seed ^ 0x5851f42d4c957f2dULL) + uint64_t(firstSample));
    photons = tracePhotons(scene, t, passSeed, counter);
  }
  return std::make_unique<PhotonPass>(std::move(photons), radius(firstSample), volumeRadius(firstSample),
                                      bandwidth(firstSample), photonsPerPass_);
}

Vec3 PpmIntegrator::directElasticOwnLanes(const Scene& scene, const Hit& hit, const Bsdf& bsdf, const Vec3& wo, float uLanes,
                                          float uLight, Vec2 uPos, SampleContext& ctx) const {
  // The camera ray and its first hit do not depend on λ, so lanes of another density estimate
  // ∫ W(λ)·L_direct,elastic(λ) dλ as well as the camera's (§3).
  const CameraLanes own = stratifiedLanes(*directLanes_, uLanes, n_);
  const SensorShares direct =
      lanesNextEvent(scene, hit, VertexMedium{}, bsdf, wo, own, elasticEvent({own.lambda, size_t(n_)}), uLight, uPos, ctx.counter);
  Vec3 xyz(0.0f);
  for (int j = 0; j < n_; ++j)
    if (direct.v[j] != 0.0f) xyz += sensorResponse(ctx, own.lambda[j], direct.v[j]);
  return xyz;
}

Vec3 PpmIntegrator::samplePixel(const Scene& scene, Vec2 pixel, Sampler& rng, SampleContext& ctx) const {
  const auto& pass = static_cast<const PhotonPass&>(*ctx.pass);
  const WavelengthDensity& p = sensor_.density();
  const float u = rng.uniform();
  const Vec2 uFilm = rng.uniform2();
  const Vec2 uLens = scene.camera.sampleLens(rng);
  CameraLanes lanes = stratifiedLanes(p, u, n_);
  float sensorLambda[kMaxLanes];  // the wavelength each sensor share is seen at
  std::copy(lanes.lambda, lanes.lambda + n_, sensorLambda);
  Ray ray = scene.camera.generateRay(scene.pixelFilter.filmPosition(pixel, uFilm), uLens);
  SensorShares L;    // radiance over density arriving at each sensor wavelength
  Vec3 xyz(0.0f);    // elastic photons seen at their own wavelengths
  // Media (docs/photon-mapping.md §9): the medium the ray travels in, and the lanes' spectral MIS
  // of free flights (as in the path tracer, whose Radiance-mode flights these are).
  const bool media = scene.hasMedia();
  int medium = scene.cameraMedium;
  LaneRatios ratios;
  ratios.reset(lanes.n);
  CameraLanes misWeighted;
  const uint32_t firstDimension = rng.dimension();
  for (int bounces = 0;; ++bounces) {
    rng.startVertex(firstDimension, bounces);
    const float uFlight = media ? freeFlightUniform(rng, firstDimension, bounces) : 0.0f;
    const FreeFlight flight =
        traceFreeFlight(scene, ray, medium, {lanes.lambda, size_t(lanes.n)}, uFlight, TransportMode::Radiance, ctx.counter);
    if (media) {
      for (int k = 0; k < lanes.n; ++k) {
        lanes.beta[k] = lanes.beta[k] * flight.weight[k];
        ratios.r[k] *= flight.ratio[k];
      }
      const float mis = ratios.misWeight();
      misWeighted.n = lanes.n;
      for (int k = 0; k < lanes.n; ++k) misWeighted.lambda[k] = lanes.lambda[k], misWeighted.beta[k] = lanes.beta[k] * mis;
    }
    // The lanes arriving here as every contribution weights them: times their share of the free
    // flights' MIS (LaneRatios), which is 1 without media.
    const CameraLanes& arriving = media ? misWeighted : lanes;
    const std::optional<Hit>& hit = flight.hit;
    const bool seesEmitters = bounces > 0 || !hideEmitters_;
    if (!hit && !flight.collided) {
      if (const EnvironmentLight* env = seesEmitters ? scene.environment() : nullptr)
        for (int k = 0; k < lanes.n; ++k) L += arriving.beta[k] * env->Le(lanes.lambda[k], ray.d);
      break;
    }
    // A surface, or a point in a medium (no shape, no normal: offsetPoint leaves it where it is).
    const Shape* shape = flight.collided ? nullptr : &scene.shapes[hit->shape];
    Hit mediumPoint;
    if (!shape) mediumPoint.p = flight.p, mediumPoint.ng = Vec3(0.0f);
    const Hit& vertex = shape ? *hit : mediumPoint;
    // Nothing on the path so far depends on the lanes' wavelengths: the camera ray's first surface
    // in a scene without media (through a medium its transmittance does).
    const bool spectrallyFree = bounces == 0 && !media;
    // Emission is hit only after the camera or specular vertices: next-event estimation and the
    // photons never count these paths (docs/photon-mapping.md §3).
    if (shape && shape->emission && seesEmitters) {
      if (spectrallyFree && !ctx.recordSpectral) {
        // Seen directly, an area emitter's L_e(λ)·[side] is known at every λ: its XYZ is exact (as
        // in the path tracer). Spectral bins need each lane's share, so they keep the lanes' estimate.
        if (shape->emission->emitsTowards(hit->ng, -ray.d)) xyz += directXyz_[size_t(scene.shapeLight[hit->shape])];
      } else {
        for (int k = 0; k < lanes.n; ++k) L += arriving.beta[k] * shape->emission->eval(lanes.lambda[k], hit->ng, -ray.d);
      }
    }
    if (bounces >= maxDepth_) break;
    const Bsdf bsdf = shape ? scene.bsdf(*hit, {lanes.lambda, size_t(lanes.n)}) : scene.mediumBsdf(flight.medium, flight.p);
    const VertexMedium where{flight.medium, shape != nullptr};
    const Vec3 wo = bsdf.toLocal(-ray.d);
    const float uLobe = rng.uniform(), uLane = rng.uniform(), uLight = rng.uniform();
    const Vec2 uPos = rng.uniform2(), uDir = rng.uniform2();
    const float uDirectLanes = rng.uniform();  // the vertex block's last dimension (docs/sampler.md)
    const std::span<const float> known(lanes.lambda, size_t(lanes.n));
    // The spectral event of every lane (Jung18 eq. 7, λ_i as the path tracer draws it; a medium's
    // collision samples its own): next-event estimation's lobe, and the lobe whose direction
    // continues the path if it is specular.
    const bool strategy = shape && excitation_.draws(shape->material);
    LaneEvent e = sampleLaneEvent(bsdf, TransportMode::Radiance, known, n_, uLobe,
                                  strategy ? &excitation_.density(shape->material) : nullptr);
    if (!bsdf.has(BsdfFlags::DeltaDirection)) {
      const int elasticFromDepth = direct_ == PpmDirectLight::Photons ? 1 : 2;
      // Surface photons in discs at a surface, volume photons in balls at a collision (§9).
      gatherPhotons(shape ? pass.surface : pass.volume, pass.bandwidth, bsdf, vertex.p, wo, arriving, bounces, maxDepth_,
                    elasticFromDepth, spectrallyFree && !alwaysKernel_, ctx, L, xyz);
      // Light sampling is the only estimator of direct light here (the path continues through
      // specular directions only): no MIS weight. "nee-elastic": the elastic lobe of every lane
      // for sure; "nee": the lobe of the spectral event e.
      // Spectral bins keep the camera's lanes: their density is the one the bins asked for, while
      // the own lanes follow the observer, whose far-red tail they would reach only rarely (§3).
      if (direct_ == PpmDirectLight::NeeElastic && spectrallyFree && directLanes_ && !ctx.recordSpectral)
        xyz += directElasticOwnLanes(scene, *hit, bsdf, wo, uDirectLanes, uLight, uPos, ctx);
      else if (direct_ != PpmDirectLight::Photons)
        L += lanesNextEvent(scene, vertex, where, bsdf, wo, arriving, direct_ == PpmDirectLight::Nee ? e : elasticEvent(known),
                            uLight, uPos, ctx.counter);
    }
    if (e.n == 0) break;
    // Lanes end where the path tracer ends them: a direction that depends on λ keeps one.
    if (e.lobe == SpectralLobe::Elastic && bsdf.has(BsdfFlags::WavelengthDependentDirection)) keepOneLane(e, uLane);
    const float lambdaOut0 = e.lobe == SpectralLobe::Elastic ? e.lambda[0] : lanes.lambda[0];
    const std::optional<DirectionSample> ds =
        bsdf.sampleDirection({TransportMode::Radiance, e.lobe, e.lambda[0], lambdaOut0}, wo, uDir);
    // The gather covers every non-specular lobe (a medium's phase function is one); a sampled
    // specular direction continues the path.
    if (!ds || !ds->specular || !(ds->pdf > 0.0f)) break;
    // Fresh lanes (fluorescent), or one lane kept: the free flights' MIS so far goes into them.
    const bool lanesChange = media && (e.lobe == SpectralLobe::Fluorescent || e.n != lanes.n);
    const CameraLanes& before = lanesChange ? arriving : lanes;
    CameraLanes next;
    next.n = e.n;
    bool alive = false;
    for (int k = 0; k < e.n; ++k) {
      next.lambda[k] = e.lambda[k];
      next.beta[k] = laneWeight(bsdf, TransportMode::Radiance, known, before.beta, e, k, ds->w, wo) * (std::abs(ds->w.z) / ds->pdf);
      alive = alive || next.beta[k].anyPositive();
    }
    if (!alive) break;
    if (lanesChange) ratios.reset(e.n);
    lanes = next;
    const Vec3 w = bsdf.toWorld(ds->w);
    ray = Ray{offsetPoint(vertex.p, vertex.ng, w), w};
    if (media) medium = where.leaving(scene, vertex, w);
  }
  // W(λ_j) times each sensor wavelength's share (docs/transport.md §1).
  for (int j = 0; j < n_; ++j)
    if (L.v[j] != 0.0f) xyz += sensorResponse(ctx, sensorLambda[j], L.v[j]);
  return xyz;
}

}  // namespace kasha
