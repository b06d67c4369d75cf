#include "integrators/photon_mapping/photon_tracer.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "integrators/chunked_paths.h"
#include "integrators/light_subpath_lanes.h"
#include "integrators/medium_transport.h"

namespace kasha {
namespace {

// Stores the lanes of positive power at p, each lane's beta times `scale`, kPhotonLanes to a photon.
void store(const Vec3& p, const Vec3& wi, const LightLanes& lanes, float scale, int depth, bool inMedium,
           std::vector<Photon>& out) {
  Photon ph{{p.x, p.y, p.z}, {wi.x, wi.y, wi.z}, 0, uint16_t(depth), inMedium, {}, {}};
  for (int k = 0; k < lanes.n; ++k) {
    const float power = lanes.beta[k] * scale;
    if (!(power > 0.0f)) continue;
    ph.lambda[ph.lanes] = lanes.lambda[k];
    ph.power[ph.lanes] = power;
    if (++ph.lanes == kPhotonLanes) {
      out.push_back(ph);
      ph.lanes = 0;
    }
  }
  if (ph.lanes > 0) out.push_back(ph);
}

// One light subpath with its lanes, as the light tracer starts and continues it (without camera
// connections), in the light tracer's dimension layout: through media by the same free flights
// (Importance mode), a collision being a vertex whose Bsdf is the medium's (BsdfFlags::Volume).
void tracePath(const Scene& scene, const PhotonTracing& s, Sampler& rng, std::vector<Photon>& out, RayCounter& counter) {
  const float uLambda = rng.uniform(), uLight = rng.uniform();
  const Vec2 uPos = rng.uniform2(), uDir = rng.uniform2();
  LightStartLanes st = startLightLanes(scene, *s.wavelengths, s.lanes, uLambda, uLight, uPos, uDir);
  if (st.lanes.n == 0) return;
  LightLanes& lanes = st.lanes;
  const float beta0 = magnitude(lanes);  // Russian roulette compares the throughput with the emitted weight
  if (!(beta0 > 0.0f)) return;
  const EmissionSample& es = st.es;
  Ray ray{glm::dot(es.n, es.n) > 0.0f ? offsetPoint(es.p, es.n, es.w) : es.p, es.w};
  // Media (docs/media.md §3): the medium the ray travels in, and the lanes' spectral MIS of free flights.
  const bool media = scene.hasMedia();
  const LightOrigin origin = lightOrigin(scene, st);
  int medium = origin.where.leaving(scene, origin.hit, es.w);
  LaneRatios ratios;
  ratios.reset(lanes.n);
  const uint32_t firstDimension = rng.dimension();
  for (int depth = 1; depth <= s.maxDepth; ++depth) {
    const std::optional<LightSubpathVertex> v = nextLightVertex(scene, ray, medium, lanes, ratios, rng, firstDimension, depth, counter);
    if (!v) break;
    const auto& [vertex, where, bsdf, mis] = *v;  // mis: the stored flux's share of the lanes' spectral MIS
    const bool inMedium = !where.onSurface;
    const Vec3 wi = bsdf.toLocal(-ray.d);
    // At a surface, stored as flux times |ω_i·n_s|/|ω_i·n_g| of this vertex, so that the gather's
    // f·Φ is Veach's shading-normal f_s·Φ (Veach97 §5.3): Φ is flux through the surface, not about
    // n_s. At a collision, beta is the flux times the free flight's T/p: its sum over a ball
    // estimates ∫∫ L(x, ω) dω dV (docs/photon-mapping.md §9). In a heterogeneous medium the
    // flight's p and the collision's kernel both leave out the density d(x) (medium_transport.h),
    // which cancels along one path; the gather meets this photon with the kernel of another point,
    // so the photon divides its own d(x_p) out.
    if (depth >= s.firstStoredDepth && !bsdf.has(BsdfFlags::DeltaDirection)) {
      const float scale = inMedium ? 1.0f / scene.media[size_t(where.medium)]->density(vertex.p) : bsdf.incidentShadingRatio(wi);
      store(vertex.p, wi, lanes, mis * scale, depth, inMedium, out);
    }
    if (depth == s.maxDepth) break;
    // The spectral event of every lane (Importance: the lobe and the wavelengths leaving here).
    const float uLobe = rng.uniform(), uLane = rng.uniform();
    LaneEvent e = sampleLaneEvent(bsdf, TransportMode::Importance, {lanes.lambda, size_t(lanes.n)}, s.lanes, uLobe);
    if (e.n == 0) break;
    if (lanesEndAt(e, bsdf)) keepOneLane(e, uLane);
    // Fresh lanes (fluorescent), or one lane kept: the free flights' MIS so far goes into them.
    if (media && (e.lobe == SpectralLobe::Fluorescent || e.n != lanes.n)) {
      for (int k = 0; k < lanes.n; ++k) lanes.beta[k] *= mis;
      ratios.reset(e.n);
    }
    const std::optional<Vec3> w = scatterLightLanes(bsdf, wi, e, lanes, depth >= s.rrDepth, beta0, rng);
    if (!w) break;
    ray = Ray{offsetPoint(vertex.p, vertex.ng, *w), *w};
    if (media) medium = where.leaving(scene, vertex, *w);
  }
}

}  // namespace

PassPhotons tracePhotons(const Scene& scene, const PhotonTracing& s, uint64_t seed, RayCounter& counter) {
  PassPhotons photons;
  photons.surface = traceInChunks<Photon>(s.paths, s.memoryLimit, kBytesPerPhoton,
                                          {"the photon map of one pass", "photons", "render/ppm/photons_per_pass"}, counter,
                                          [&](size_t j, std::vector<Photon>& out, RayCounter& rays) {
                                            Sampler rng(s.sampler, seed, 0, uint32_t(j));
                                            tracePath(scene, s, rng, out, rays);
                                          });
  // The collisions' photons moved out in path order (within the two records per photon of kBytesPerPhoton).
  std::vector<Photon>& all = photons.surface;
  const auto inMedium = [](const Photon& ph) { return ph.inMedium; };
  const size_t volume = size_t(std::count_if(all.begin(), all.end(), inMedium));
  if (volume == 0) return photons;
  photons.volume.reserve(volume);
  std::copy_if(all.begin(), all.end(), std::back_inserter(photons.volume), inMedium);
  all.erase(std::remove_if(all.begin(), all.end(), inMedium), all.end());
  return photons;
}

}  // namespace kasha
