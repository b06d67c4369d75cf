#include "integrators/bdpt/subpaths.h"

#include "core/color.h"
#include "integrators/bdpt/subpath_mis.h"

namespace kasha::bdpt {
namespace {

float laneSum(const float* beta, int n) {
  float sum = 0.0f;
  for (int k = 0; k < n; ++k) sum += beta[k];
  return sum;
}

// Extends `path` from its last vertex along `ray` (Veach's random walk). pdfSA is the density of
// ray's direction at the last vertex (per steradian; for a light at infinity, per unit area of
// its disk). Camera walks run in Radiance mode, light walks in Importance mode; a walk with
// stopAtFluorescence ends at its first fluorescent event (the shared family's light subpaths).
void randomWalk(const Scene& scene, Ray ray, const float* betaStart, float pdfSA, const Lanes& lanes, TransportMode mode,
                bool stopAtFluorescence, const WalkSettings& ws, Sampler& rng, RayCounter& counter, std::vector<PathVertex>& path) {
  const bool camera = mode == TransportMode::Radiance;
  float beta[kMaxLanes];
  std::copy(betaStart, betaStart + lanes.n, beta);
  const float beta0 = laneSum(beta, lanes.n);
  float lambda = lanes.lambda[0];
  int lane = lanes.n > 1 ? -1 : 0;  // every lane alive, or the one kept (a one-lane subpath: its only lane)
  int surfaces = 0;
  for (;;) {
    const std::optional<Hit> hit = scene.accel->intersect(ray);
    ++counter.closest;
    PathVertex& prev = path.back();
    if (!hit) {
      if (camera && scene.environment()) {  // the camera path escapes to the environment
        PathVertex v;
        v.kind = PathVertex::Kind::Infinite;
        v.dir = -ray.d;
        v.light = scene.environmentLight;
        std::copy(beta, beta + lanes.n, v.beta);
        v.lane = int8_t(lane);
        v.lambda = lambda;
        v.pdfFwd = pdfSA;
        path.push_back(v);
        updateSums(path, mode);
      }
      return;
    }
    PathVertex v;
    v.kind = PathVertex::Kind::Surface;
    v.p = hit->p;
    v.n = hit->ng;
    v.bsdf = lane < 0 ? scene.bsdf(*hit, {lanes.lambda, size_t(lanes.n)}) : scene.bsdf(*hit, {&lambda, 1});
    v.light = scene.shapeLight[hit->shape];
    // Where sampling depends on the wavelength, the lanes end in one chosen at random, its weight
    // times n (docs/bdpt-mis.md §10): every density on the subpath is then that lane's.
    // Elsewhere the densities are those of any lane that scatters here (docs/bdpt-mis.md §10).
    if (lanes.n > 1 && lane < 0) {
      const float uLane = rng.uniform();
      v.laneU = uLane;
      if (v.bsdf->has(BsdfFlags::Fluorescent) || v.bsdf->has(BsdfFlags::WavelengthDependentDirection)) {
        lane = std::min(int(uLane * float(lanes.n)), lanes.n - 1);
        lambda = lanes.lambda[lane];
        for (int k = 0; k < lanes.n; ++k) beta[k] = k == lane ? beta[k] * float(lanes.n) : 0.0f;
      } else {
        lambda = lanes.lambda[0];
        for (int k = 0; k < lanes.n; ++k)
          if (beta[k] > 0.0f && v.bsdf->spectralPdf(mode, lanes.lambda[k], lanes.lambda[k], SpectralLobe::Elastic) > 0.0f) {
            lambda = lanes.lambda[k];
            break;
          }
      }
    }
    std::copy(beta, beta + lanes.n, v.beta);
    v.lane = int8_t(lane);
    v.lambda = lambda;
    v.pdfFwd = prev.kind == PathVertex::Kind::Infinite ? pdfSA * std::abs(glm::dot(v.n, ray.d))  // disk → surface
                                                        : toAreaDensity(pdfSA, prev, v);
    path.push_back(v);
    updateSums(path, mode);
    ++surfaces;
    // Vertices up to maxDepth sample their spectral event (used by next-event estimation and
    // the camera connection); camera vertices then extend up to maxDepth (the next one may be an
    // emitter hit), light vertices while a path through the next one can end within maxDepth.
    if (surfaces > ws.maxDepth) return;
    PathVertex& cur = path.back();
    const Bsdf& bsdf = *cur.bsdf;
    const Vec3 wKnown = bsdf.toLocal(-ray.d);
    const SpectralChoice sc = bsdf.sampleSpectral(mode, lambda, rng.uniform());
    if (sc.pdf <= 0.0f) return;
    cur.lobe = sc.lobe;
    cur.lambdaNext = sc.lambda;
    cur.spectralPdf = sc.pdf;
    cur.eventSampled = true;
    if (!camera && surfaces == ws.maxDepth) return;
    if (stopAtFluorescence && sc.lobe == SpectralLobe::Fluorescent) return;
    const float lambdaIn = camera ? sc.lambda : lambda, lambdaOut = camera ? lambda : sc.lambda;
    const std::optional<DirectionSample> ds =
        bsdf.sampleDirection(mode, wKnown, sc.lobe, lambdaIn, lambdaOut, rng.uniform2());
    if (!ds || ds->pdf <= 0.0f) return;
    const Vec3 wi = camera ? ds->w : wKnown, wo = camera ? wKnown : ds->w;
    cur.specular = ds->specular;
    const float pdfFwd = sc.pdf * ds->pdf;
    const float pdfRev = bsdf.spectralPdf(flip(mode), sc.lambda, lambda, sc.lobe) *
                         bsdf.directionPdf(flip(mode), ds->w, wKnown, sc.lobe, lambdaIn, lambdaOut);
    // The other side's density of the previous vertex. A delta light or the pinhole cannot be
    // reached by the other side at all.
    PathVertex& before = path[path.size() - 2];
    if (before.kind == PathVertex::Kind::Camera || before.deltaPosition ||
        (before.kind == PathVertex::Kind::Infinite && scene.lights[size_t(before.light)]->isDelta()))
      before.pdfRev = 0.0f;
    else
      before.pdfRev = toAreaDensity(pdfRev, cur, before);
    // Every lane alive here scatters elastically through a wavelength-independent density.
    for (int k = cur.firstLane(); k < cur.endLane(lanes); ++k) {
      const float f = cur.allLanes(lanes) ? bsdf.eval(mode, wi, wo, lanes.lambda[k], lanes.lambda[k], sc.lobe)
                                          : bsdf.eval(mode, wi, wo, lambdaIn, lambdaOut, sc.lobe);
      beta[k] *= f * std::abs(ds->w.z) / pdfFwd;
    }
    const float sum = laneSum(beta, lanes.n);
    if (!(sum > 0.0f)) return;
    lambda = sc.lambda;
    pdfSA = pdfFwd;
    const Vec3 w = bsdf.toWorld(ds->w);
    ray = Ray{offsetPoint(cur.p, cur.n, w), w};
    if (surfaces >= ws.rrDepth) {  // Russian roulette against the starting throughput
      const float q = std::min(1.0f, sum / beta0);
      if (rng.uniform() >= q) return;
      for (int k = 0; k < lanes.n; ++k) beta[k] /= q;
    }
  }
}

}  // namespace

Lanes sensorLanes(const Scene& scene, const WavelengthDensity& sensor, float u, int n, LaneLightTable& table,
                  const WavelengthDensity* own) {
  Lanes lanes;
  lanes.n = n;
  for (int k = 0; k < n; ++k) {
    const WavelengthSample ws = sensor.sample(laneStratum(u, k, n));
    lanes.lambda[k] = ws.lambda;
    lanes.sensorPdf[k] = ws.pdf;
    lanes.response[k] = Observer::cie1931().weight(ws.lambda);
    lanes.lightPdf[k] = own && n > 1 ? own->pdf(ws.lambda) : 0.0f;
  }
  if (n > 1) {
    table.reset(scene, {lanes.lambda, size_t(n)});
    lanes.lights = &table;
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
  c.p = scene.camera.position();
  std::fill(c.beta, c.beta + lanes.n, 1.0f);
  c.lambda = lanes.lambda[0];
  c.pdfFwd = 1.0f;
  c.deltaPosition = true;
  out.push_back(c);
  updateSums(out, TransportMode::Radiance);
  const Ray ray = scene.camera.generateRay(filmPos);
  // The sensor's density of the last wavelength group is a factor of the weights (mis_sums.h).
  const float pdfDir = scene.camera.directionPdf(ray.d);
  randomWalk(scene, ray, c.beta, pdfDir, lanes, TransportMode::Radiance, false, ws, rng, counter, out);
}

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
  const float lambda = lanes.lambda[0];
  const Vec2 uPos = rng.uniform2(), uDir = rng.uniform2();
  if (choice <= 0.0f) return;
  const Light& L = *scene.lights[light];
  const std::optional<EmissionSample> es = L.sampleEmission(lambda, uPos, uDir);
  if (!es || es->pdfPos <= 0.0f || es->pdfDir <= 0.0f) return;
  PathVertex v;
  v.kind = L.atInfinity() ? PathVertex::Kind::Infinite : PathVertex::Kind::Light;
  v.p = es->p;
  v.n = es->n;
  v.dir = es->w;
  v.light = int(light);
  v.lambda = lambda;
  if (lanes.n == 1) v.lane = 0;
  v.deltaPosition = es->deltaPos;
  // At infinity the light vertex is a direction (density per sr) and the disk position is the
  // density of the first surface point; otherwise the position is the vertex. The light choice is
  // a factor of the weights (mis_sums.h).
  const float start = L.atInfinity() ? es->pdfDir : es->pdfPos;
  v.pdfFwd = start;
  v.choicePdf = choice;
  float beta[kMaxLanes];
  for (int k = 0; k < lanes.n; ++k) {
    // The emission's geometry does not depend on λ: the same point and direction at every lane's.
    const float Le = k == 0 ? es->Le : L.emitted(*es, lanes.lambda[k]);
    v.beta[k] = Le / (choice * start);
    beta[k] = Le * es->cosOrigin / (choice * es->pdfPos * es->pdfDir);
  }
  if (!(laneSum(v.beta, lanes.n) > 0.0f)) return;
  out.push_back(v);
  updateSums(out, TransportMode::Importance);
  const Vec3 origin = glm::dot(es->n, es->n) > 0.0f ? offsetPoint(es->p, es->n, es->w) : es->p;
  randomWalk(scene, Ray{origin, es->w}, beta, L.atInfinity() ? es->pdfPos : es->pdfDir, lanes,
             TransportMode::Importance, family == LightFamily::Shared, ws, rng, counter, out);
}

}  // namespace kasha::bdpt
