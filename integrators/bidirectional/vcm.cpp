#include "integrators/bidirectional/vcm.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/memory_budget.h"
#include "integrators/bidirectional/connect.h"
#include "integrators/bidirectional/family_pilot.h"
#include "integrators/bidirectional/merge.h"
#include "integrators/bidirectional/path_media.h"
#include "integrators/bidirectional/pilot_observer.h"
#include "integrators/bidirectional/strategy_images.h"
#include "integrators/bidirectional/subpath_mis.h"
#include "integrators/direct_emission.h"
#include "integrators/integrator_factory.h"
#include "integrators/beams_near_segments.h"
#include "integrators/points_near_segments.h"
#include "integrators/progressive_schedule.h"
#include "integrators/bidirectional/light_vertex_pass.h"

namespace kasha {
namespace {

// The default r_1 puts this many light vertices in a disc if a pass's vertices spread evenly over
// all surfaces. Photon mapping's default holds 16 photons (docs/photon-mapping.md); merged with
// the connections, a radius that large gives the merges most of the weight of diffuse light (η is
// large) and their noise with it, so vcm's holds one, as small as SmallVCM's (0.3% of the scene's
// radius): merges then carry mostly the paths that connections cannot make, such as caustics.
constexpr float kVerticesPerDisc = 1.0f;
// The default volume radius r_v,1: a sphere around a light vertex in a medium holds this many others
// (docs/media.md §6), as the disc of a surface merge holds kVerticesPerDisc.
constexpr double kVerticesPerSphere = 1.0;
// The wide gather's radius over the pass's (VcmPaths::Gather): its disc holds 16 times the light
// vertices, as many as photon mapping's (docs/photon-mapping.md).
constexpr float kGatherScale = 4.0f;
// What a merge weight computed costs, in rays (the pilot's cost model): 0.28, 0.26, 0.28 and 0.34 on
// yamamoto_leds, jung18_fig1, jung18_fig3 and viewing_booth, from the extra time per sample of the
// wide gather over the extra merge weights it computes (8 spp, 1 thread, the fastest of 4 runs of
// --vcm-paths bidirectional and gather, in bidirectional's time per ray; docs/bdpt-mis.md §14).
constexpr double kRaysPerMergeWeight = 0.28;
// Light subpaths of the pilot that counts the vertices a pass keeps per subpath.
constexpr size_t kPilotPaths = 1024;
// Light subpaths of each of the subpath pilot's passes, at most (docs/bdpt-mis.md §14).
constexpr size_t kPilotLightPaths = 8192;
// The pixels, and samples per pixel, at which the subpath pilot measures what camera paths alone
// gain from stratified random numbers (docs/bdpt-mis.md §14).
constexpr size_t kGainPixels = 512;
constexpr int kGainSpp = 16;

// The radius of a sphere around a light vertex in a medium that holds `count` other such vertices
// of `vertices` on average, by bisection on the counts (it adapts to thin media, where the count
// grows as the area of a slab's cross-section); `fallback` where fewer than two lie in media.
float sphereHolding(const std::vector<bidir::LightVertex>& vertices, double count, float fallback) {
  std::vector<bidir::LightVertex> inMedia;
  for (const bidir::LightVertex& v : vertices)
    if (v.has(bidir::LightVertex::kMedium)) inMedia.push_back(v);
  if (inMedia.size() < 2) return fallback;
  Vec3 lo(kInf), hi(-kInf);
  for (const bidir::LightVertex& v : inMedia) {
    lo = glm::min(lo, Vec3(v.p[0], v.p[1], v.p[2]));
    hi = glm::max(hi, Vec3(v.p[0], v.p[1], v.p[2]));
  }
  const LightVertexMap map(std::move(inMedia));
  double small = 0.0, large = double(glm::length(hi - lo)) + 1e-6;
  for (int i = 0; i < 32; ++i) {
    const double r = 0.5 * (small + large);
    size_t others = 0;
    for (size_t j = 0; j < map.size(); ++j) {
      const bidir::LightVertex& v = map[j];
      others += map.within(Vec3(v.p[0], v.p[1], v.p[2]), float(r)).size() - 1;
    }
    (double(others) / double(map.size()) < count ? small : large) = r;
  }
  return float(large);
}

}  // namespace

// What every camera sample of a pass shares: its wavelength lanes, the walk with this pass's η, and
// the light vertices to merge with; or, where camera paths alone run, pt's pass.
struct VcmPass final : PassData {
  // Sets the radius and η of own merges through a fluorescent lobe at the first gather vertex:
  // the pass's, or kGatherScale times its radius (MergeEta). The light vertices do not depend on it.
  void setGather(bool wide) {
    const float scale = wide ? kGatherScale : 1.0f;
    radiusGather = radius * scale;
    walk.strategies.merge.gather = walk.strategies.merge.eta * double(scale) * scale;
  }

  bidir::LaneTables tables;
  bidir::Lanes lanes;
  bidir::WalkSettings walk;
  float radius = 0.0f;
  float radiusVolume = 0.0f;  // merges at collisions in media (0: the scene has none)
  float radiusGather = 0.0f;  // own merges through a fluorescent lobe at the first gather vertex (MergeEta)
  float bandwidth = 0.0f;  // the wavelength kernel's half-width (own merges through an elastic lobe); 0: none
  std::unique_ptr<LightVertexMap> vertices;  // null without merges
  // With beams: the light vertices in media (indices into `vertices`) near the camera's query beams,
  // within radiusVolume across them (docs/media-beams.md).
  std::unique_ptr<PointsNearSegments> beamPoints;
  std::vector<size_t> beamVertices;
  // And the light subpaths' flights through homogeneous media, photon beams, near them within a
  // cylinder of radius radiusVolume (docs/media-beams.md eq. B5).
  std::vector<bidir::PhotonBeam> photonBeams;
  std::unique_ptr<BeamsNearSegments> beamsNear;
  bool cameraAlone = false;
  std::unique_ptr<const PassData> camera;    // cameraAlone: what pt's beginPass returned
};

Vcm::Vcm(const Scene& scene, const RenderSettings& s, Parts parts)
    : sensor_(s.wavelengths.sensor, WavelengthSources(scene), WavelengthSite::Sensor),
      light_(s.wavelengths.light, WavelengthSources(scene), WavelengthSite::LightStart),
      parts_(parts),
      ws_{s.maxDepth, s.rrDepth, &light_.density(), nullptr, {}, s.hideEmitters},
      families_(bidir::familiesFor(scene, bidir::WavelengthMode::Unified)),
      lanes_(s.heroWavelengths == kAutoLanes ? kDefaultLanes : s.heroWavelengths),
      alpha_(s.vcm.alpha),
      memoryLimit_(s.memoryLimit),
      sampler_(s.sampler),
      directXyz_(directEmissionXyz(scene)) {
  requireDensity(s.wavelengths.sensor, WavelengthSite::Sensor, "by " + name() + " (its MIS weights need the sensor's density)");
  requireDensity(s.wavelengths.light, WavelengthSite::LightStart,
                 "by " + name() + " (its MIS weights need the light-start density)");
  // In scenes with media, separate light subpaths per family, as bdpt's (docs/media.md §5).
  const bool media = scene.hasMedia();
  if (media) bidir::requireBidirectionalMedia(s, name());
  if (lanes_ < 1 || lanes_ > bidir::kLightVertexLanes)
    throw std::invalid_argument(name() + ": hero wavelengths " + std::to_string(lanes_) + " is outside [1, " +
                                std::to_string(bidir::kLightVertexLanes) + "] (the lanes a light vertex keeps)");
  if (families_.independent && !media) {
    lightFirst_ = std::make_unique<bidir::LightFirstStart>(scene, s.wavelengths.light);
    ws_.lightFirst = lightFirst_.get();
  }
  const VcmSettings& p = s.vcm;
  checkProgressiveSettings(p, [&](const char* key, const std::string& why) {
    throw std::invalid_argument(name() + ": render/vcm/" + key + " " + why);
  });
  // SmallVCM's choice: as many light subpaths per pass as pixels.
  paths_ = p.photonsPerPass > 0 ? size_t(p.photonsPerPass) : size_t(scene.camera.width()) * size_t(scene.camera.height());
  double area = 0.0;
  for (const Shape& shape : scene.shapes) area += shape.area;
  // A subpath keeps several vertices in a closed, bright scene: count them on a pilot of subpaths
  // (at the lanes of the first pass), so that the default radius holds kVerticesPerDisc of them.
  // In media the same pilot sets the volume radius: a sphere holds kVerticesPerSphere of the pass's
  // light vertices in media.
  double kept = double(paths_);
  const bool mergesInMedia = media && parts_ != Parts::Connections;
  std::vector<bidir::LightVertex> pilotVertices;
  LightVertexTracing pilot;
  pilot.paths = std::min(kPilotPaths, paths_);
  if ((p.radius <= 0.0f || (mergesInMedia && p.volumeRadius <= 0.0f)) && parts_ != Parts::Connections) {
    bidir::LaneTables tables;
    const bidir::Lanes lanes = bidir::sensorLanes(scene, sensor_.density(), 0.5f, lanes_, tables, nullptr, lightFirst_.get());
    pilot.sampler = sampler_;
    pilot.memoryLimit = UINT64_MAX;  // at most kPilotPaths·max_depth·2 vertices
    pilot.ownFamily = families_.independent && !lightFirst_;
    RayCounter rays;
    pilotVertices = traceLightVertices(scene, lanes, ws_, pilot, 0x9e3779b97f4a7c15ULL, rays);
    const auto onSurfaces = std::count_if(pilotVertices.begin(), pilotVertices.end(), [](const bidir::LightVertex& v) {
      return !v.has(bidir::LightVertex::kMedium);
    });
    kept = std::max(1.0, double(onSurfaces) * double(paths_) / double(pilot.paths));
  }
  radius1_ = p.radius > 0.0f ? p.radius : float(std::sqrt(kVerticesPerDisc * area / (kPi * kept)));
  beams_ = mergesInMedia && p.beams;
  photonBeams_ = beams_ && p.photonBeams;
  if (mergesInMedia)
    volumeRadius1_ = p.volumeRadius > 0.0f ? p.volumeRadius
                                           : sphereHolding(pilotVertices, kVerticesPerSphere * double(pilot.paths) / double(paths_),
                                                           radius1_);
  // Own light vertices merge through an elastic lobe with a wavelength kernel, as photon mapping's
  // (render/vcm/bandwidth, by default 1% of the range), shrinking with the radius.
  if (parts_ != Parts::Connections && families_.independent)
    bandwidth1_ = p.bandwidth > 0.0f ? p.bandwidth : 0.01f * (scene.range.max - scene.range.min);
  ws_.strategies.connections = parts_ != Parts::Merges;
  // Without light subpaths vertex connection and merging is path tracing with next-event
  // estimation (its strategies s = 0 and s = 1): pt's estimator, at the same wavelength settings.
  if (parts_ == Parts::ConnectionsAndMerges) pathsChoice_ = s.vcm.paths;
  if (pathsChoice_ == VcmPaths::Auto || pathsChoice_ == VcmPaths::Camera) {
    RenderSettings camera = s;
    camera.wavelengths.light = WavelengthSettings().light;  // pt traces no light subpaths
    cameraAlone_ = makeIntegrator("pt", scene, camera);
  }
}

Vcm::~Vcm() = default;

std::string Vcm::name() const {
  return parts_ == Parts::Merges ? "bpm" : parts_ == Parts::Connections ? "vc" : "vcm";
}

float Vcm::radius(int sample) const { return std::sqrt(progressiveRadiusSquared(radius1_, alpha_, sample + 1)); }

float Vcm::volumeRadius(int sample) const { return progressiveRadius(volumeRadius1_, alpha_, sample + 1, 3); }

std::unique_ptr<const PassData> Vcm::beginPass(const Scene& scene, int firstSample, int count, uint64_t seed,
                                               RayCounter& counter) const {
  VcmPaths run = pathsChoice_;
  if (run == VcmPaths::Auto) {
    // Every process runs the pilot once; its rays count in the pass that takes sample 0, so that the
    // statistics do not depend on the number of processes (render_group.h).
    RayCounter pilotRays;
    run = pilotChoice(scene, seed, pilotRays);
    if (firstSample == 0) counter.closest += pilotRays.closest, counter.shadow += pilotRays.shadow;
  }
  if (run != VcmPaths::Camera) return bidirectionalPass(scene, firstSample, seed, run, counter);
  auto pass = std::make_unique<VcmPass>();
  pass->cameraAlone = true;
  pass->camera = cameraAlone_->beginPass(scene, firstSample, count, seed, counter);
  return pass;
}

VcmPaths Vcm::pilotChoice(const Scene& scene, uint64_t seed, RayCounter& counter) const {
  std::lock_guard<std::mutex> lock(pilotMutex_);
  if (pilot_ && pilot_->seed == seed) return pilot_->run;
  using namespace bidir;
  // Passes of its own (lanes, light vertices), one per sample of a pixel of each image, as a render
  // takes one per sample per pixel: two images of vcm against them, and from their paths what
  // camera paths alone and the connections alone would add (PilotMoments, Alone::Camera and
  // Alone::Connections); then two with the wide gather, against the same light vertices.
  const int w = scene.camera.width(), h = scene.camera.height();
  RayCounter passRays;
  std::vector<std::unique_ptr<VcmPass>> passes;
  std::vector<const PassData*> passData;
  const uint64_t passSeed = mixBits(seed ^ 0xa0761d6478bd642fULL);
  for (int i = 0; i < 2 * pilotSamplesPerImage(w, h); ++i) {
    passes.push_back(bidirectionalPass(scene, i, passSeed, VcmPaths::Bidirectional, passRays, kPilotLightPaths));
    passData.push_back(passes.back().get());
  }
  // The render's light subpaths per pass over the pilot's.
  const double passShare = double(paths_) / double(std::min(kPilotLightPaths, paths_)) / double(passes.size());
  // The alternatives weighed from vcm's paths: excess[0] and unsampled[0] camera paths alone's,
  // [1] the connections alone's.
  constexpr Alone kWeighed[2] = {Alone::Camera, Alone::Connections};
  std::atomic<uint64_t> unsampled[2] = {0, 0};
  std::atomic<uint64_t> weights[2] = {0, 0};  // merge weights computed: without and with the wide gather
  const PilotSample both = [&](Vec2 pixel, Sampler& rng, SampleContext& ctx,
                               std::vector<std::vector<Splat>>& excess) -> Vec3 {
    thread_local PilotMoments moments;
    moments.clear();
    PilotObserver observer(moments);
    const Vec3 v = estimate(scene, pixel, rng, ctx, static_cast<const VcmPass&>(*ctx.pass), &observer);
    weights[0].fetch_add(observer.count, std::memory_order_relaxed);
    for (int a = 0; a < 2; ++a) {
      const PilotMoments::Alternative& alt = moments.alone[int(kWeighed[a])];
      if (alt.unsampled > 0) unsampled[a].fetch_add(uint64_t(alt.unsampled), std::memory_order_relaxed);
      excess[size_t(a)].insert(excess[size_t(a)].end(), alt.excess.begin(), alt.excess.end());
    }
    return v;
  };
  const PilotEstimates e = pilotEstimates(w, h, seed, SamplerKind::Independent, 2, both, passData);
  // The wide gather widens own merges only: without own light vertices it is vcm itself.
  const bool gatherDiffers = families_.independent;
  for (const std::unique_ptr<VcmPass>& pass : passes) pass->setGather(gatherDiffers);
  const PilotSample wide = [&](Vec2 pixel, Sampler& rng, SampleContext& ctx, std::vector<std::vector<Splat>>&) {
    MergeWeightCount merges;
    const Vec3 v = estimate(scene, pixel, rng, ctx, static_cast<const VcmPass&>(*ctx.pass), &merges);
    weights[1].fetch_add(merges.count, std::memory_order_relaxed);
    return v;
  };
  const PilotEstimates g = gatherDiffers ? pilotEstimates(w, h, seed, SamplerKind::Independent, 1, wide, passData) : e;
  // The connections alone's rays per sample, from samples of their own against a pass without light
  // vertices.
  RayCounter connectionRays;  // no light vertices: the pass traces none
  const std::unique_ptr<VcmPass> connectionPass =
      bidirectionalPass(scene, 0, passSeed, VcmPaths::Connections, connectionRays);
  const PilotSample connections = [&](Vec2 pixel, Sampler& rng, SampleContext& ctx, std::vector<std::vector<Splat>>&) {
    return estimate(scene, pixel, rng, ctx, *connectionPass, nullptr);
  };
  const double connectionsRays = raysPerSample(w, h, seed, connections, connectionRays);
  const PilotSample camera = [&](Vec2 pixel, Sampler& rng, SampleContext& ctx, std::vector<std::vector<Splat>>&) {
    return cameraAlone_->samplePixel(scene, pixel, rng, ctx);
  };
  // What camera paths alone gain from the render's stratified random numbers over independent
  // ones, from their own samples (light they rarely find is missing from both alike).
  RayCounter cameraRays;
  const double independent =
      relativeVarianceAtPixels(w, h, seed, SamplerKind::Independent, kGainSpp, kGainPixels, camera, cameraRays);
  double gain = 1.0;
  int kinds = 1;
  if (sampler_ != SamplerKind::Independent) {
    const double stratified = relativeVarianceAtPixels(w, h, seed, sampler_, kGainSpp, kGainPixels, camera, cameraRays);
    gain = independent > 0.0 ? stratified / independent : 1.0;
    kinds = 2;
  }
  const double cameraSamples = double(kinds) * 2.0 * kGainSpp * double(std::min(kGainPixels, size_t(w) * size_t(h)));
  const RayCounter gRays = gatherDiffers ? g.rays : RayCounter{};
  counter.closest = e.rays.closest + gRays.closest + connectionRays.closest + passRays.closest + cameraRays.closest;
  counter.shadow = e.rays.shadow + gRays.shadow + connectionRays.shadow + passRays.shadow + cameraRays.shadow;
  PilotOutcome o;
  o.seed = seed;
  o.relVar = e.relVar;
  // Per camera sample: its own rays and its share of the pass's light subpaths (a pass takes one
  // sample per pixel).
  o.rays = double(e.rays.closest + e.rays.shadow) / double(e.samples) +
           double(passRays.closest + passRays.shadow) * passShare / (double(w) * double(h));
  o.cameraSamplesAll = unsampled[0].load() == 0;
  o.stratification = gain;
  o.cameraRelVar = (e.relVar + e.relExcess[0]) * gain;
  o.cameraRays = double(cameraRays.closest + cameraRays.shadow) / cameraSamples;
  // The wide gather traces the same rays; each merge weight computed costs kRaysPerMergeWeight rays.
  o.cost = o.rays + kRaysPerMergeWeight * double(weights[0].load()) / double(e.samples);
  o.gatherDiffers = gatherDiffers;
  o.gatherRelVar = g.relVar;
  o.gatherCost = gatherDiffers ? o.rays + kRaysPerMergeWeight * double(weights[1].load()) / double(g.samples) : o.cost;
  // The connections alone trace no light vertices and compute no merge weights.
  o.connectionsSamplesAll = unsampled[1].load() == 0;
  o.connectionsRelVar = e.relVar + e.relExcess[1];
  o.connectionsRays = connectionsRays;
  double best = o.relVar * o.cost;
  if (o.gatherRelVar * o.gatherCost < best) o.run = VcmPaths::Gather, best = o.gatherRelVar * o.gatherCost;
  if (o.connectionsSamplesAll && o.connectionsRelVar * o.connectionsRays < best)
    o.run = VcmPaths::Connections, best = o.connectionsRelVar * o.connectionsRays;
  if (o.cameraSamplesAll && o.cameraRelVar * o.cameraRays < best) o.run = VcmPaths::Camera;
  pilot_ = o;
  return o.run;
}

std::string Vcm::choices() const {
  if (!cameraAlone_) return {};
  if (pathsChoice_ != VcmPaths::Auto) return std::string("paths: ") + toString(pathsChoice_);
  std::lock_guard<std::mutex> lock(pilotMutex_);
  if (!pilot_) return {};
  char camera[160];
  if (pilot_->cameraSamplesAll)
    std::snprintf(camera, sizeof camera, "%.3g, %.3g rays (stratification x%.2g)", pilot_->cameraRelVar,
                  pilot_->cameraRays, pilot_->stratification);
  else
    std::snprintf(camera, sizeof camera, "cannot sample some paths that carry light");
  char connections[96] = "cannot sample some paths that carry light";
  if (pilot_->connectionsSamplesAll)
    std::snprintf(connections, sizeof connections, "%.3g, %.3g rays", pilot_->connectionsRelVar, pilot_->connectionsRays);
  char gather[80] = "the same (no own light vertices)";
  if (pilot_->gatherDiffers)
    std::snprintf(gather, sizeof gather, "%.3g, %.3g rays", pilot_->gatherRelVar, pilot_->gatherCost);
  char buf[480];
  std::snprintf(buf, sizeof buf,
                "paths: %s (pilot: relative variance per sample and cost per sample in rays: bidirectional %.3g, "
                "%.3g rays; gather %s; connections alone %s; camera alone %s)",
                toString(pilot_->run), pilot_->relVar, pilot_->cost, gather, connections, camera);
  return buf;
}

std::unique_ptr<VcmPass> Vcm::bidirectionalPass(const Scene& scene, int firstSample, uint64_t seed, VcmPaths run,
                                                RayCounter& counter, size_t paths) const {
  auto pass = std::make_unique<VcmPass>();
  // The pass's lanes: sample `firstSample` of a sequence of its own, so that passes stratify them.
  Sampler laneRng(sampler_, mixBits(seed ^ 0x2545f4914f6cdd1dULL), 0, uint32_t(firstSample));
  pass->lanes = bidir::sensorLanes(scene, sensor_.density(), laneRng.uniform(), lanes_, pass->tables,
                                  families_.independent ? &light_.density() : nullptr, lightFirst_.get());
  pass->walk = ws_;
  // The connections alone are vc's: no merges, and no wavelength kernel (bandwidth1_ is 0 in vc).
  if (parts_ == Parts::Connections || run == VcmPaths::Connections) return pass;
  const float r = radius(firstSample);
  pass->bandwidth = bandwidth1_ * r / radius1_;
  // Fewer light subpaths than the render's (the pilot) merge within a radius widened so that η, and
  // with it the merges' weights and the light vertices a disc holds, stay the pass's.
  paths = paths == 0 ? paths_ : std::min(paths, paths_);
  pass->radius = r * float(std::sqrt(double(paths_) / double(paths)));
  const double eta = double(paths_) * kPi * double(r) * r;
  // Merges at collisions in media: a sphere of radius r_v, η_v = N·(4/3)π r_v³ (docs/media.md §6).
  const float rv = volumeRadius(firstSample);
  pass->radiusVolume = rv * float(std::cbrt(double(paths_) / double(paths)));
  const double etaVolume = double(paths_) * (4.0 / 3.0) * kPi * double(rv) * rv * rv;
  pass->walk.strategies.merge = {eta, eta, etaVolume, pass->radiusVolume, !scene.hasMedia()};
  // Beams: the pass's light vertices in media against a disc of radius r_v across each query beam,
  // η_b = N·π r_v² of the light subpaths traced (docs/media-beams.md eq. B2), and their flights
  // through homogeneous media within a cylinder of the same radius around each, whose chord through
  // the query is 2r_v/sin θ: η_pb = N·π r_v²/(2r_v) (eq. B4).
  if (beams_) {
    const double etaBeam = double(paths) * kPi * double(pass->radiusVolume) * pass->radiusVolume;
    pass->walk.strategies.merge.beam = etaBeam;
    if (photonBeams_) pass->walk.strategies.merge.photonBeam = etaBeam / (2.0 * double(pass->radiusVolume));
  }
  pass->setGather(run == VcmPaths::Gather);
  LightVertexTracing t;
  t.paths = paths;
  t.sampler = sampler_;
  t.memoryLimit = memoryLimit_;
  t.ownFamily = families_.independent && !lightFirst_;
  // A stream family per pass, apart from the camera samples' (render_loop.cpp) and the lanes'.
  const uint64_t passSeed = mixBits(mixBits(seed ^ 0x5851f42d4c957f2dULL) + uint64_t(firstSample));
  pass->vertices = std::make_unique<LightVertexMap>(
      traceLightVertices(scene, pass->lanes, pass->walk, t, passSeed, counter, photonBeams_ ? &pass->photonBeams : nullptr));
  if (beams_) {
    std::vector<Vec3> points;
    for (size_t i = 0; i < pass->vertices->size(); ++i) {
      const bidir::LightVertex& v = (*pass->vertices)[i];
      if (!v.has(bidir::LightVertex::kMedium)) continue;
      pass->beamVertices.push_back(i);
      points.emplace_back(v.p[0], v.p[1], v.p[2]);
    }
    if (!points.empty()) pass->beamPoints = std::make_unique<PointsNearSegments>(points, pass->radiusVolume);
    std::vector<BeamsNearSegments::Beam> segments;
    segments.reserve(pass->photonBeams.size());
    for (const bidir::PhotonBeam& b : pass->photonBeams) segments.push_back({b.origin, b.w, b.length});
    if (!segments.empty()) pass->beamsNear = std::make_unique<BeamsNearSegments>(segments, pass->radiusVolume);
  }
  return pass;
}

Vec3 Vcm::samplePixel(const Scene& scene, Vec2 pixel, Sampler& rng, SampleContext& ctx) const {
  const VcmPass& pass = static_cast<const VcmPass&>(*ctx.pass);
  if (!pass.cameraAlone) return estimate(scene, pixel, rng, ctx, pass, nullptr);
  ctx.pass = pass.camera.get();
  const Vec3 xyz = cameraAlone_->samplePixel(scene, pixel, rng, ctx);
  ctx.pass = &pass;
  return xyz;
}

Vec3 Vcm::estimate(const Scene& scene, Vec2 pixel, Sampler& rng, SampleContext& ctx, const VcmPass& pass,
                   bidir::MisObserver* observer) const {
  using namespace bidir;
  const Lanes& lanes = pass.lanes;
  for (int k = 0; k < lanes_; ++k)
    if (lanes.pdf[k] <= 0.0f) return Vec3(0.0f);
  thread_local std::vector<PathVertex> C, LS, LO;  // the camera subpath, the light subpath's two views
  const Vec2 film = scene.pixelFilter.filmPosition(pixel, rng.uniform2());
  traceCameraSubpath(scene, film, lanes, pass.walk, rng, ctx.counter, C);
  Context c{scene, pass.walk, families_, lanes, sensor_.density(), ctx.counter};
  c.spectralSplats = ctx.recordSpectral;
  c.bandwidth = pass.bandwidth;
  c.pixel = pixel;
  if (lanes_ > 1 && !ctx.recordSpectral && !scene.hasMedia()) c.directXyz = &directXyz_;
  // The pilot's samples do not record strategies (pilotEstimates).
  StrategyLog log(ctx.strategies);
  c.observer = ctx.recordStrategies ? &log : observer;
  float radiance[kMaxLanes];
  Vec3 xyz(0.0f);
  if (parts_ != Parts::Merges) {
    // The connections: one light subpath per camera sample, as the unified bdpt's.
    LS.clear(), LO.clear();
    if (lightFirst_) {
      c.sharedLightVertices = traceMergedLightSubpath(scene, lanes, pass.walk, rng, ctx.counter, LS, LO);
    } else {
      traceLightSubpath(scene, LightFamily::Shared, lanes, pass.walk, rng, ctx.counter, LS);
      if (families_.independent) traceLightSubpath(scene, LightFamily::Own, lanes, pass.walk, rng, ctx.counter, LO);
    }
    connectSubpaths(c, C, LS, LO, rng, ctx.splats, radiance, xyz);
  } else {
    std::fill(radiance, radiance + lanes_, 0.0f);
    for (int t = pass.walk.hideEmitters ? 3 : 2; t <= int(C.size()); ++t) emitterHit(c, C, t, radiance, xyz);
  }
  if (pass.vertices) {
    thread_local std::vector<SpectralSample> atLight;  // merges at the light vertices' own wavelengths
    atLight.clear();
    const int maxDepth = pass.walk.maxDepth;
    for (int t = 2; t <= int(C.size()) && t - 1 <= maxDepth; ++t) {
      const PathVertex& b = C[size_t(t - 1)];
      if (!mergeable(b, true)) continue;
      // A collision merges with the light vertices in media within r_v, a surface point with those on
      // surfaces within r (own ones through a fluorescent first gather vertex within the gather's).
      const bool volume = b.inMedium();
      const float r = volume ? pass.radiusVolume : pass.radius;
      const float r2 = r * r;
      const float reach = !volume && b.gather ? std::max(pass.radius, pass.radiusGather) : r;
      const std::vector<size_t>& near = pass.vertices->within(b.p, reach);
      for (size_t i : near) {
        const LightVertex& v = (*pass.vertices)[i];
        if (v.has(LightVertex::kMedium) != volume) continue;
        const Vec3 d = Vec3(v.p[0], v.p[1], v.p[2]) - b.p;
        if (v.depth + t - 2 <= maxDepth) merge(c, C, t, v, glm::dot(d, d) <= r2, radiance, atLight);
      }
    }
    // The light vertices in media, and the photon beams, near each query beam (docs/media-beams.md).
    thread_local std::vector<PointsNearSegments::Found> nearBeam;
    thread_local std::vector<uint32_t> nearPhotonBeams;
    for (int t = 2; (pass.beamPoints || pass.beamsNear) && t <= int(C.size()) && t - 1 <= maxDepth; ++t) {
      const std::optional<QueryBeam> q = queryBeam(c, C, t);
      if (!q) continue;
      nearBeam.clear(), nearPhotonBeams.clear();
      if (pass.beamPoints) pass.beamPoints->near(q->origin, q->w, q->length, nearBeam);
      for (const PointsNearSegments::Found& f : nearBeam) {
        const LightVertex& v = (*pass.vertices)[pass.beamVertices[f.index]];
        if (v.depth + t - 2 <= maxDepth) mergeBeam(c, C, t, *q, f.t, v, radiance);
      }
      if (pass.beamsNear) pass.beamsNear->near(q->origin, q->w, q->length, nearPhotonBeams);
      for (uint32_t i : nearPhotonBeams) {
        const PhotonBeam& beam = pass.photonBeams[i];
        if (beam.medium != q->medium || beam.vertex.depth + t - 2 > maxDepth) continue;
        if (const std::optional<BeamCrossing> x = crossing(*q, beam, pass.radiusVolume, rng.uniform()))
          mergePhotonBeam(c, C, t, *q, beam, *x, radiance);
      }
    }
    for (const SpectralSample& a : atLight) xyz += sensorResponse(ctx, a.lambda, a.value);
  }
  // Each lane's radiance weighted by W(λ_k)/(n·p(λ_k)), as bdpt's.
  for (int k = 0; k < lanes_; ++k)
    xyz += sensorResponse(ctx, lanes.lambda[k], lanes.response[k], radiance[k] / (float(lanes_) * lanes.pdf[k]));
  return xyz;
}

}  // namespace kasha
