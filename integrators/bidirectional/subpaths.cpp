#include "integrators/bidirectional/subpaths.h"

#include <algorithm>
#include <limits>

#include "core/color.h"
#include "integrators/bidirectional/path_media.h"
#include "integrators/bidirectional/subpath_mis.h"

namespace kasha::bidir {
namespace {

float laneSum(const float* beta, int n) {
  float sum = 0.0f;
  for (int k = 0; k < n; ++k) sum += beta[k];
  return sum;
}

// One subpath traced along a walk's rays: a walk carries one, or two where the unified estimator
// merges its light subpaths (docs/bdpt-mis.md §11).
struct Track {
  const Lanes* lanes = nullptr;
  std::vector<PathVertex>* path = nullptr;
  float beta[kMaxLanes] = {};
  float beta0 = 0.0f;  // the lanes' starting throughput, for Russian roulette
  float lambda = 0.0f;
  int lane = 0;        // -1 every lane alive, else the one kept (a one-lane subpath: its only lane)
  float pdfSA = 0.0f;  // density of the ray's direction at the last vertex, its spectral event included
  int medium = -1;     // the medium the ray travels in (scenes with media)
  bool alive = true;
  bool stopAtFluorescence = false;  // the shared family: ends at its first fluorescent event
  // The merged subpath's shared lanes (docs/bdpt-mis.md §11): where sampling depends on the
  // wavelength and the own view goes on too, they leave the walk and go on alone from there
  // (forked, with the ray that reached the vertex and the walk's count of surfaces).
  bool forkWhereLambdaDependent = false;
  bool forked = false;
  Ray forkRay;
  int forkSurfaces = 0;
  SpectralChoice event;  // the spectral event sampled at the last vertex
};

bool lambdaDependent(const Bsdf& bsdf) {
  return bsdf.has(BsdfFlags::Fluorescent) || bsdf.has(BsdfFlags::WavelengthDependentDirection);
}

// Ends the track's lanes in the hero lane 0, its throughput times n (docs/bdpt-mis.md §10): every
// density on the subpath from here on is that lane's. Lane 0 is the member of the lane set that the
// sensor's own number picks, so it is uniform among them, and the sampler stratifies it over the
// pixel's samples; the camera and light subpaths keep the same one.
void keepLaneZero(Track& tr) {
  const Lanes& lanes = *tr.lanes;
  tr.lane = 0;
  tr.lambda = lanes.lambda[0];
  for (int k = 1; k < lanes.n; ++k) tr.beta[k] = 0.0f;
  tr.beta[0] *= float(lanes.n);
}

Track startTrack(const Lanes& lanes, std::vector<PathVertex>& path, const float* betaStart, float pdfSA, int medium) {
  Track tr;
  tr.medium = medium;
  tr.lanes = &lanes;
  tr.path = &path;
  std::copy(betaStart, betaStart + lanes.n, tr.beta);
  tr.beta0 = laneSum(tr.beta, lanes.n);
  tr.lambda = lanes.lambda[0];
  tr.lane = lanes.n > 1 ? -1 : 0;
  tr.pdfSA = pdfSA;
  return tr;
}

// Appends the scattering vertex `reached` (a surface or medium point: its place, scattering
// function, light, media and arrival set), reached along `ray`, to the track's subpath: completed in
// place (a vertex is about 500 bytes; it is copied once, into the subpath).
void arrive(Track& tr, const PathVertex& reached, const Ray& ray, const Scene& scene, TransportMode mode,
            const Strategies& st, Sampler& rng, RayCounter& counter) {
  const Lanes& lanes = *tr.lanes;
  std::vector<PathVertex>& path = *tr.path;
  path.push_back(reached);
  PathVertex& v = path.back();
  PathVertex& prev = path[path.size() - 2];
  const Bsdf& bsdf = *v.bsdf;
  v.lanesKept = prev.lanesKept && !lambdaDependent(bsdf) && !v.arrival.inMedia;
  v.gather = !prev.scatters() || (prev.gather && !prev.joinable(false));
  if (v.inMedium() && st.merge.volume > 0.0)
    v.sphereInMedium = sphereClearOfSurfaces(scene, v.p, float(st.merge.volumeRadius), counter);
  // Where sampling depends on the wavelength, the lanes end on arrival in the hero lane 0
  // (keepLaneZero). Elsewhere the densities are those of any lane that scatters here
  // (docs/bdpt-mis.md §10).
  if (lanes.n > 1 && tr.lane < 0) {
    v.laneU = rng.uniform();
    if (lambdaDependent(bsdf)) {
      v.lanesEndHere = true;
      std::copy(tr.beta, tr.beta + lanes.n, v.betaArriving);
      keepLaneZero(tr);
    } else {
      tr.lambda = lanes.lambda[0];
      for (int k = 0; k < lanes.n; ++k)
        if (tr.beta[k] > 0.0f && bsdf.spectralPdf(mode, lanes.lambda[k], lanes.lambda[k], SpectralLobe::Elastic) > 0.0f) {
          tr.lambda = lanes.lambda[k];
          break;
        }
    }
  }
  std::copy(tr.beta, tr.beta + lanes.n, v.beta);
  v.lane = int8_t(tr.lane);
  v.lambda = tr.lambda;
  v.pdfFwd = (prev.kind == PathVertex::Kind::Infinite ? tr.pdfSA * v.cosine(ray.d)  // disk → surface
                                                       : toAreaDensity(tr.pdfSA, prev, v)) *
             flightFactor(scene, mode, v.arrival, v, v.lambda);
  // The camera side's beam ratio over the segment just flown: of v on a camera subpath, of the
  // previous vertex on a light subpath (which the camera side reaches from v); the light side's the
  // other way round.
  if (st.merge.beam > 0.0 || st.merge.photonBeam > 0.0) {
    PathVertex& camera = mode == TransportMode::Radiance ? v : prev;
    PathVertex& light = mode == TransportMode::Radiance ? prev : v;
    camera.cameraBeam = float(cameraBeamRatio(scene, v.arrival, camera, v.lambda));
    if (st.merge.photonBeam > 0.0) {
      light.lightBeam = float(lightBeamRatio(scene, v.arrival, light, camera, v.lambda));
      // prev's two segments are known now.
      if (path.size() >= 3 && prev.inMedium()) prev.beamSine = crossingSine(prev.p, path[path.size() - 3].p, v.p);
    }
  }
  updateSums(path, mode, st);
}

// The track's spectral event at its last vertex, sampled with u; false if it cannot go on.
bool sampleEvent(Track& tr, TransportMode mode, float u) {
  PathVertex& cur = tr.path->back();
  const SpectralChoice sc = cur.bsdf->sampleSpectral(mode, tr.lambda, u);
  if (sc.pdf <= 0.0f) return false;
  cur.lobe = sc.lobe;
  cur.lambdaNext = sc.lambda;
  cur.spectralPdf = sc.pdf;
  cur.eventSampled = true;
  tr.event = sc;
  return true;
}

// The track's throughput and densities through its last vertex's event along the sampled
// direction ds (local frame; wKnown the direction it arrived from); false if no lane goes on.
bool scatter(Track& tr, const Scene& scene, TransportMode mode, const Vec3& wKnown, const DirectionSample& ds) {
  const bool camera = mode == TransportMode::Radiance;
  std::vector<PathVertex>& path = *tr.path;
  const Lanes& lanes = *tr.lanes;
  PathVertex& cur = path.back();
  const Bsdf& bsdf = *cur.bsdf;
  const SpectralChoice& sc = tr.event;
  const float lambdaIn = camera ? sc.lambda : tr.lambda, lambdaOut = camera ? tr.lambda : sc.lambda;
  const Vec3 wi = camera ? ds.w : wKnown, wo = camera ? wKnown : ds.w;
  cur.specular = ds.specular;
  const float pdfFwd = sc.pdf * ds.pdf;
  const float pdfRev = bsdf.spectralPdf(flip(mode), sc.lambda, tr.lambda, sc.lobe) *
                       bsdf.directionPdf({flip(mode), sc.lobe, lambdaIn, lambdaOut}, ds.w, wKnown);
  // The other side's density of the previous vertex. A delta light or the pinhole cannot be
  // reached by the other side at all.
  PathVertex& before = path[path.size() - 2];
  if (before.kind == PathVertex::Kind::Camera || before.deltaPosition ||
      (before.kind == PathVertex::Kind::Infinite && scene.lights[size_t(before.light)]->isDelta()))
    before.pdfRev = 0.0f;
  else
    before.pdfRev = toAreaDensity(pdfRev, cur, before) * flightFactor(scene, flip(mode), cur.arrival, before, cur.lambda);
  // Every lane alive here scatters elastically through a wavelength-independent density.
  for (int k = cur.firstLane(); k < cur.endLane(lanes); ++k) {
    const float f = cur.allLanes(lanes) ? bsdf.eval({mode, sc.lobe, lanes.lambda[k], lanes.lambda[k]}, wi, wo)
                                        : bsdf.eval({mode, sc.lobe, lambdaIn, lambdaOut}, wi, wo);
    tr.beta[k] *= f * bsdf.cosineFactor(ds.w) / pdfFwd;
  }
  tr.lambda = sc.lambda;
  tr.pdfSA = pdfFwd;
  return laneSum(tr.beta, lanes.n) > 0.0f;
}

// Extends the tracks' subpaths along `ray` from their last vertex (one point), or with atVertex from
// the vertex `ray` reached, after `surfaces` surface vertices (Veach's random walk). Camera walks run
// in Radiance mode, light walks in Importance mode. Where two tracks share the walk (the merged
// light subpath, docs/bdpt-mis.md §11), they go on together through the vertices whose sampling
// does not depend on λ: both scatter elastically there with a wavelength-independent direction
// density, which the first live track samples. At any other, a forking track leaves the walk.
void randomWalk(const Scene& scene, Ray ray, Track* tracks, int nTracks, TransportMode mode, const WalkSettings& ws,
                Sampler& rng, RayCounter& counter, int surfaces = 0, bool atVertex = false) {
  const bool camera = mode == TransportMode::Radiance;
  const bool media = scene.hasMedia();
  auto live = [&] { return std::find_if(tracks, tracks + nTracks, [](const Track& t) { return t.alive; }); };
  for (bool arrived = atVertex;; arrived = false) {
    if (!arrived) {
      // Through the media (one track in scenes with media, bdpt.cpp; docs/media.md §5), at the
      // track's wavelength, or where several lanes fly, at lane 0's: a flight through a medium ends
      // them in lane 0 (keepLaneZero), since its density depends on λ; whether it runs through one
      // does not. The flight's weight T/p goes into the throughput.
      Track& lead = tracks[0];
      const float uFlight = media ? rng.uniform() : 0.0f;
      const float flightLambda = lead.lane < 0 ? lead.lanes->lambda[0] : lead.lambda;
      const FreeFlight flight = traceFreeFlight(scene, ray, lead.medium, {&flightLambda, 1}, uFlight, mode, counter, true);
      if (flight.depth.inMedia && lead.lane < 0) keepLaneZero(lead);
      if (media) lead.beta[0] *= flight.weight[0];
      if (!flight.hit && !flight.collided) {
        if (camera && scene.environment()) {  // the camera path escapes to the environment
          PathVertex v;
          v.kind = PathVertex::Kind::Infinite;
          v.dir = -ray.d;
          v.light = scene.environmentLight;
          std::copy(lead.beta, lead.beta + lead.lanes->n, v.beta);
          v.lane = int8_t(lead.lane);
          v.lambda = lead.lambda;
          v.arrival = flight.depth;
          if (media) v.flightWeight = flight.weight[0];
          v.pdfFwd = lead.pdfSA * flightFactor(scene, mode, v.arrival, v, v.lambda);
          v.lanesKept = lead.path->back().lanesKept && !v.arrival.inMedia;
          lead.path->push_back(v);
          updateSums(*lead.path, mode, ws.strategies);
        }
        return;
      }
      PathVertex v;
      if (flight.collided) {
        v.kind = PathVertex::Kind::Medium;
        v.p = flight.p;
        v.bsdf = scene.mediumBsdf(flight.medium, flight.p);
      } else {
        const Hit& hit = *flight.hit;
        v.p = hit.p;
        v.n = hit.ng;
        v.bsdf = scene.bsdf(hit, {lead.lanes->lambda, size_t(lead.lanes->n)});
        v.light = scene.shapeLight[hit.shape];
        v.shape = int(hit.shape);
      }
      v.medium = flight.medium;
      v.arrival = flight.depth;
      if (media) v.flightWeight = flight.weight[0];
      const Bsdf& bsdf = *v.bsdf;
      int alive = 0;
      for (int i = 0; i < nTracks; ++i)
        if (tracks[i].alive) arrive(tracks[i], v, ray, scene, mode, ws.strategies, rng, counter), ++alive;
      ++surfaces;
      if (alive > 1 && lambdaDependent(bsdf))
        for (int i = 0; i < nTracks; ++i)
          if (tracks[i].alive && tracks[i].forkWhereLambdaDependent) {
            tracks[i].alive = false;
            tracks[i].forked = true;
            tracks[i].forkRay = ray;
            tracks[i].forkSurfaces = surfaces;
          }
    }
    // Vertices up to maxDepth sample their spectral event (used by next-event estimation and
    // the camera connection); camera vertices then extend up to maxDepth (the next one may be an
    // emitter hit), light vertices while a path through the next one can end within maxDepth.
    if (surfaces > ws.maxDepth) return;
    const PathVertex& at = live()->path->back();
    const Bsdf& bsdf = *at.bsdf;
    const Vec3 wKnown = bsdf.toLocal(-ray.d);
    const float uSpectral = rng.uniform();
    for (int i = 0; i < nTracks; ++i)
      if (tracks[i].alive && !sampleEvent(tracks[i], mode, uSpectral)) tracks[i].alive = false;
    if (!camera && surfaces == ws.maxDepth) return;
    for (int i = 0; i < nTracks; ++i)
      if (tracks[i].stopAtFluorescence && tracks[i].event.lobe == SpectralLobe::Fluorescent) tracks[i].alive = false;
    const Track* driver = live();
    if (driver == tracks + nTracks) return;
    const SpectralChoice& sc = driver->event;
    const float lambdaIn = camera ? sc.lambda : driver->lambda, lambdaOut = camera ? driver->lambda : sc.lambda;
    const std::optional<DirectionSample> ds =
        bsdf.sampleDirection({mode, sc.lobe, lambdaIn, lambdaOut}, wKnown, rng.uniform2());
    if (!ds || ds->pdf <= 0.0f) return;
    float q = 0.0f;
    for (int i = 0; i < nTracks; ++i) {
      Track& tr = tracks[i];
      if (tr.alive && !scatter(tr, scene, mode, wKnown, *ds)) tr.alive = false;
      if (tr.alive) q = std::max(q, laneSum(tr.beta, tr.lanes->n) / tr.beta0);
    }
    if (live() == tracks + nTracks) return;
    const Vec3 w = bsdf.toWorld(ds->w);
    ray = Ray{offsetPoint(at.p, at.n, w), w};
    if (media)
      for (int i = 0; i < nTracks; ++i) tracks[i].medium = mediumToward(scene, at, w);
    if (surfaces >= ws.rrDepth) {  // Russian roulette against the starting throughput
      q = std::min(1.0f, q);
      if (rng.uniform() >= q) return;
      for (int i = 0; i < nTracks; ++i)
        if (tracks[i].alive)
          for (int k = 0; k < tracks[i].lanes->n; ++k) tracks[i].beta[k] /= q;
    }
  }
}

}  // namespace

Families familiesFor(const Scene& scene, WavelengthMode mode) {
  using M = WavelengthMode;
  bool fluoresces = scene.hasFluorescentMedia();
  for (const auto& m : scene.materials) fluoresces = fluoresces || has(m->flags(), BsdfFlags::Fluorescent);
  return {mode != M::Independent, mode == M::Independent || (mode == M::Unified && fluoresces)};
}

Lanes sensorLanes(const Scene& scene, const WavelengthDensity& sensor, float u, int n, LaneTables& tables,
                  const WavelengthDensity* own, const LightFirstStart* merged) {
  Lanes lanes;
  static_cast<SampledLanes&>(lanes) = sampleLanes(sensor, u, n);
  for (int k = 0; k < n; ++k) {
    lanes.response[k] = Observer::cie1931().weight(lanes.lambda[k]);
    lanes.lightPdf[k] = own && !merged && n > 1 ? own->pdf(lanes.lambda[k]) : 0.0f;
  }
  if (n > 1) {
    tables.lights.reset(scene, {lanes.lambda, size_t(n)}, /*perLane=*/true);
    lanes.lights = &tables.lights;
  }
  if (n > 1 && merged) {
    std::vector<float>& ownStart = tables.ownStart;
    const size_t lights = scene.lights.size();
    ownStart.resize(size_t(n) * lights);
    for (int k = 0; k < n; ++k)
      for (size_t l = 0; l < lights; ++l)
        ownStart[size_t(k) * lights + l] = merged->lightProbability(l) * merged->wavelengthPdf(l, lanes.lambda[k]);
    lanes.ownStart = ownStart.data();
  }
  return lanes;
}

std::pair<size_t, float> selectLight(const Scene& scene, const Lanes& lanes, float u) {
  if (lanes.n == 1) return scene.lightSelector->select(lanes.lambda[0], u);
  return lanes.lights->select(u);
}

void traceCameraSubpath(const Scene& scene, Vec2 filmPos, const Lanes& lanes, const WalkSettings& ws, Sampler& rng,
                        RayCounter& counter, std::vector<PathVertex>& out) {
  out.clear();
  PathVertex c;
  c.kind = PathVertex::Kind::Camera;
  const Ray ray = scene.camera.generateRay(filmPos, scene.camera.sampleLens(rng));
  c.p = ray.o;
  c.medium = scene.cameraMedium;
  std::fill(c.beta, c.beta + lanes.n, 1.0f);
  c.lambda = lanes.lambda[0];
  // The lens point's density is the same in every strategy (each samples the lens alike): a
  // common factor, left out (docs/bdpt-mis.md §2).
  c.pdfFwd = 1.0f;
  c.deltaPosition = scene.camera.pinhole();
  c.parallelRays = scene.camera.parallelRays();
  out.push_back(c);
  updateSums(out, TransportMode::Radiance, ws.strategies);
  // The sensor's density of the last wavelength group is a factor of the weights (mis_sums.h); the
  // reconstruction filter's coverage turns the camera's uniform density into the camera samples'.
  const PixelFilter& filter = scene.pixelFilter;
  const float pdfRay = scene.camera.rayPdf(ray, filter.filmMargin()) *
                       filter.coverage(filmPos, scene.camera.width(), scene.camera.height());
  Track tr = startTrack(lanes, out, c.beta, pdfRay, c.medium);
  randomWalk(scene, ray, &tr, 1, TransportMode::Radiance, ws, rng, counter);
}

namespace {

// A light subpath's first vertex L[0] on light `light` from its emission sample (taken at
// sampledLambda), with its lanes' throughput Le/(choice·pL_0) and the throughput leaving along the
// sample's direction (betaOut); false if no lane carries light.
bool startLightVertex(const Scene& scene, const Light& L, size_t light, const EmissionSample& es, float sampledLambda,
                      const Lanes& lanes, float choice, PathVertex& v, float* betaOut) {
  v.kind = L.atInfinity() ? PathVertex::Kind::Infinite : PathVertex::Kind::Light;
  v.p = es.p;
  v.n = es.n;
  v.dir = es.w;
  v.light = int(light);
  v.medium = scene.lightMedium[light];
  v.shape = scene.emittingShape(L, es);
  v.lambda = lanes.lambda[0];
  if (lanes.n == 1) v.lane = 0;
  v.deltaPosition = es.deltaPos;
  // At infinity the light vertex is a direction (density per sr) and the disk position is the
  // density of the first surface point; otherwise the position is the vertex. The light choice is
  // a factor of the weights (mis_sums.h).
  const float start = L.atInfinity() ? es.pdfDir : es.pdfPos;
  v.pdfFwd = start;
  v.choicePdf = choice;
  for (int k = 0; k < lanes.n; ++k) {
    // The emission's geometry does not depend on λ: the same point and direction at every lane's.
    const float Le = lanes.lambda[k] == sampledLambda ? es.Le : L.emitted(es, lanes.lambda[k]);
    v.beta[k] = Le / (choice * start);
    betaOut[k] = Le * es.cosOrigin / (choice * es.pdfPos * es.pdfDir);
  }
  return laneSum(v.beta, lanes.n) > 0.0f;
}

Ray emissionRay(const EmissionSample& es) {
  const Vec3 origin = glm::dot(es.n, es.n) > 0.0f ? offsetPoint(es.p, es.n, es.w) : es.p;
  return Ray{origin, es.w};
}

// The density of the emission ray's direction (per unit area of the disk for a light at infinity).
float emissionDirectionPdf(const Light& L, const EmissionSample& es) { return L.atInfinity() ? es.pdfPos : es.pdfDir; }

}  // namespace

void traceLightSubpath(const Scene& scene, LightFamily family, const Lanes& shared, const WalkSettings& ws, Sampler& rng,
                       RayCounter& counter, std::vector<PathVertex>& out) {
  out.clear();
  size_t light = 0;
  Lanes lanes = shared;
  float choice = 0.0f;
  const float u1 = rng.uniform(), u2 = rng.uniform();
  if (family == LightFamily::Own) {
    const LightSelector::LightWavelength lw = scene.lightSelector->sampleLightAndWavelength(*ws.lightWavelengths, u1, u2);
    light = lw.light, lanes.n = 1, lanes.lambda[0] = lw.lambda, choice = lw.pdf;
  } else {
    const auto [l, p] = selectLight(scene, lanes, u2);
    light = l, choice = p;
  }
  const Vec2 uPos = rng.uniform2(), uDir = rng.uniform2();
  if (choice <= 0.0f) return;
  const Light& L = *scene.lights[light];
  const std::optional<EmissionSample> es = L.sampleEmission(lanes.lambda[0], uPos, uDir);
  if (!es || es->pdfPos <= 0.0f || es->pdfDir <= 0.0f) return;
  PathVertex v;
  float beta[kMaxLanes];
  if (!startLightVertex(scene, L, light, *es, lanes.lambda[0], lanes, choice, v, beta)) return;
  out.push_back(v);
  updateSums(out, TransportMode::Importance, ws.strategies);
  Track tr = startTrack(lanes, out, beta, emissionDirectionPdf(L, *es), mediumToward(scene, v, es->w));
  tr.stopAtFluorescence = family == LightFamily::Shared;
  randomWalk(scene, emissionRay(*es), &tr, 1, TransportMode::Importance, ws, rng, counter);
}

int traceMergedLightSubpath(const Scene& scene, const Lanes& shared, const WalkSettings& ws, Sampler& rng,
                            RayCounter& counter, std::vector<PathVertex>& LS, std::vector<PathVertex>& LO) {
  LS.clear(), LO.clear();
  const float uLight = rng.uniform(), uLambda = rng.uniform();
  const Vec2 uPos = rng.uniform2(), uDir = rng.uniform2();
  const LightFirstStart::Draw d = ws.lightFirst->sample(uLight, uLambda);
  if (!(d.lightPdf > 0.0f)) return 0;
  Lanes own = shared;
  own.n = 1, own.lambda[0] = d.lambda;
  const Light& L = *scene.lights[d.light];
  // The emission's geometry does not depend on λ: one sample serves both views.
  const std::optional<EmissionSample> es = L.sampleEmission(d.lambda, uPos, uDir);
  if (!es || es->pdfPos <= 0.0f || es->pdfDir <= 0.0f) return 0;
  Track tracks[2];
  int n = 0;
  PathVertex v;
  float beta[kMaxLanes];
  const float pdfDir = emissionDirectionPdf(L, *es);
  // Scenes with media do not merge the light subpaths (bdpt.cpp): no medium here.
  if (startLightVertex(scene, L, d.light, *es, d.lambda, own, d.lightPdf * d.wavelengthPdf, v, beta)) {
    LO.push_back(v);
    updateSums(LO, TransportMode::Importance, ws.strategies);
    tracks[n++] = startTrack(own, LO, beta, pdfDir, -1);
  }
  v = PathVertex{};
  if (startLightVertex(scene, L, d.light, *es, d.lambda, shared, d.lightPdf, v, beta)) {
    LS.push_back(v);
    updateSums(LS, TransportMode::Importance, ws.strategies);
    tracks[n] = startTrack(shared, LS, beta, pdfDir, -1);
    tracks[n].stopAtFluorescence = true;
    tracks[n++].forkWhereLambdaDependent = true;
  }
  if (n == 0) return 0;
  randomWalk(scene, emissionRay(*es), tracks, n, TransportMode::Importance, ws, rng, counter);
  Track& lanes = tracks[n - 1];
  if (!lanes.forked) return std::numeric_limits<int>::max();
  // The shared lanes go on alone from the vertex where they forked, as a shared subpath would.
  lanes.alive = true;
  randomWalk(scene, lanes.forkRay, &lanes, 1, TransportMode::Importance, ws, rng, counter, lanes.forkSurfaces, true);
  return lanes.forkSurfaces + 1;
}

}  // namespace kasha::bidir
