#include "integrators/photon_mapping/photon_tracer.h"

#include <cmath>

#include "integrators/chunked_paths.h"
#include "integrators/light_subpath_lanes.h"

namespace kasha {
namespace {

// Stores the lanes of positive power at `hit`, each lane's beta times `shading`, kPhotonLanes to a photon.
void store(const Hit& hit, const Vec3& wi, const LightLanes& lanes, float shading, int depth, std::vector<Photon>& out) {
  Photon ph{{hit.p.x, hit.p.y, hit.p.z}, {wi.x, wi.y, wi.z}, 0, uint16_t(depth), {}, {}};
  for (int k = 0; k < lanes.n; ++k) {
    const float power = lanes.beta[k] * shading;
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
// connections), in the light tracer's dimension layout.
void tracePath(const Scene& scene, const PhotonTracing& s, Sampler& rng, std::vector<Photon>& out, RayCounter& counter) {
  const float uLambda = rng.uniform(), uLight = rng.uniform();
  const Vec2 uPos = rng.uniform2(), uDir = rng.uniform2();
  LightStartLanes st = startLightLanes(scene, *s.wavelengths, s.lanes, uLambda, uLight, uPos, uDir);
  if (st.lanes.n == 0) return;
  LightLanes& lanes = st.lanes;
  const float beta0 = lanes.sum();  // Russian roulette compares the throughput with the emitted weight
  if (!(beta0 > 0.0f)) return;
  const EmissionSample& es = st.es;
  Ray ray{glm::dot(es.n, es.n) > 0.0f ? offsetPoint(es.p, es.n, es.w) : es.p, es.w};
  const uint32_t firstDimension = rng.dimension();
  for (int depth = 1; depth <= s.maxDepth; ++depth) {
    rng.startVertex(firstDimension, depth - 1);
    const std::optional<Hit> hit = scene.accel->intersect(ray);
    ++counter.closest;
    if (!hit) break;
    const Bsdf bsdf = scene.bsdf(*hit, {lanes.lambda, size_t(lanes.n)});
    const Vec3 wi = bsdf.toLocal(-ray.d);
    // Stored as flux times |ω_i·n_s|/|ω_i·n_g| of this vertex, so that the gather's f·Φ is Veach's
    // shading-normal f_s·Φ (Veach97 §5.3): Φ is flux through the surface, not about n_s.
    if (depth >= s.firstStoredDepth && !bsdf.has(BsdfFlags::DeltaDirection))
      store(*hit, wi, lanes, bsdf.incidentShadingRatio(wi), depth, out);
    if (depth == s.maxDepth) break;
    // The spectral event of every lane (Importance: the lobe and the wavelengths leaving here).
    const float uLobe = rng.uniform(), uLane = rng.uniform();
    LaneEvent e = sampleLaneEvent(bsdf, TransportMode::Importance, {lanes.lambda, size_t(lanes.n)}, s.lanes, uLobe);
    if (e.n == 0) break;
    if (lanesEndAt(e, bsdf)) keepOneLane(e, uLane);
    const std::optional<Vec3> w = scatterLightLanes(bsdf, wi, e, lanes, depth >= s.rrDepth, beta0, rng);
    if (!w) break;
    ray = Ray{offsetPoint(hit->p, hit->ng, *w), *w};
  }
}

}  // namespace

std::vector<Photon> tracePhotons(const Scene& scene, const PhotonTracing& s, uint64_t seed, RayCounter& counter) {
  return traceInChunks<Photon>(s.paths, s.memoryLimit, kBytesPerPhoton,
                               {"the photon map of one pass", "photons", "render/ppm/photons_per_pass"}, counter,
                               [&](size_t j, std::vector<Photon>& out, RayCounter& rays) {
                                 Sampler rng(s.sampler, seed, 0, uint32_t(j));
                                 tracePath(scene, s, rng, out, rays);
                               });
}

}  // namespace kasha
