#include "integrators/photon_mapping/photon_tracer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "core/memory_budget.h"

namespace kasha {
namespace {

constexpr size_t kPathsPerChunk = 1024;

// One light subpath, as the light tracer starts and continues it (without camera connections).
void tracePath(const Scene& scene, const PhotonTracing& s, Sampler& rng, std::vector<Photon>& out, RayCounter& counter) {
  const LightSelector::LightWavelength lw = scene.lightSelector->sampleLightAndWavelength(*s.wavelengths, rng.uniform(), rng.uniform());
  if (lw.pdf <= 0.0f) return;
  const Vec2 uPos = rng.uniform2(), uDir = rng.uniform2();
  const std::optional<EmissionSample> es = scene.lights[lw.light]->sampleEmission(lw.lambda, uPos, uDir);
  if (!es || es->pdfPos <= 0.0f || es->pdfDir <= 0.0f) return;
  // Flux per subpath: Le·cos/(p_pos·p_dir·p(light, λ)).
  float beta = es->Le * es->cosOrigin / (es->pdfPos * es->pdfDir * lw.pdf);
  if (!(beta > 0.0f)) return;
  const float beta0 = beta;  // Russian roulette compares the throughput with the emitted weight
  float lambda = lw.lambda;
  Ray ray{glm::dot(es->n, es->n) > 0.0f ? offsetPoint(es->p, es->n, es->w) : es->p, es->w};
  for (int depth = 1; depth <= s.maxDepth; ++depth) {
    const std::optional<Hit> hit = scene.accel->intersect(ray);
    ++counter.closest;
    if (!hit) break;
    const Bsdf bsdf = scene.bsdf(*hit, {&lambda, 1});
    const Vec3 wi = bsdf.toLocal(-ray.d);
    // Stored as flux times |ω_i·n_s|/|ω_i·n_g| of this vertex, so that the gather's f·Φ is Veach's
    // shading-normal f_s·Φ (Veach97 §5.3): Φ is flux through the surface, not about n_s.
    const float power = beta * bsdf.incidentShadingRatio(wi);
    if (depth >= s.firstStoredDepth && !bsdf.has(BsdfFlags::DeltaDirection) && power > 0.0f)
      out.push_back({{hit->p.x, hit->p.y, hit->p.z}, {wi.x, wi.y, wi.z}, lambda, power, uint32_t(depth)});
    if (depth == s.maxDepth) break;
    // Both stages in Importance mode: lobe and λ_o (Jung18 eq. 6), then the direction.
    const std::optional<ScatterSample> ss =
        bsdf.sample(TransportMode::Importance, wi, lambda, rng.uniform3());
    if (!ss) break;
    beta *= ss->f * std::abs(ss->w.z) / ss->pdf;
    if (!(beta > 0.0f)) break;
    lambda = ss->lambda;
    const Vec3 w = bsdf.toWorld(ss->w);
    ray = Ray{offsetPoint(hit->p, hit->ng, w), w};
    if (depth >= s.rrDepth) {
      const float q = std::min(1.0f, beta / beta0);
      if (rng.uniform() >= q) break;
      beta /= q;
    }
  }
}

}  // namespace

std::vector<Photon> tracePhotons(const Scene& scene, const PhotonTracing& s, uint64_t seed, RayCounter& counter) {
  const size_t chunks = (s.paths + kPathsPerChunk - 1) / kPathsPerChunk;
  std::vector<std::vector<Photon>> parts(chunks);
  std::vector<RayCounter> counters(chunks);
  const size_t maxStored = size_t(s.memoryLimit / kBytesPerPhoton);
  std::atomic<size_t> stored{0};
  std::atomic<bool> overflow{false};
  tbb::parallel_for(tbb::blocked_range<size_t>(0, chunks, 1), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t c = range.begin(); c < range.end() && !overflow.load(std::memory_order_relaxed); ++c) {
      const size_t end = std::min(s.paths, (c + 1) * kPathsPerChunk);
      for (size_t j = c * kPathsPerChunk; j < end; ++j) {
        Sampler rng(s.sampler, seed, 0, uint32_t(j));
        tracePath(scene, s, rng, parts[c], counters[c]);
      }
      if (stored.fetch_add(parts[c].size()) + parts[c].size() > maxStored) overflow = true;
    }
  });
  for (const RayCounter& c : counters) counter.closest += c.closest;
  const size_t total = stored.load();
  if (overflow)
    requireMemory(saturatingMul(total, kBytesPerPhoton),
                  "the photon map of one pass (at least " + std::to_string(total) + " photons × " +
                      std::to_string(kBytesPerPhoton) + " bytes from " + std::to_string(s.paths) +
                      " light subpaths; lower render/ppm/photons_per_pass)",
                  s.memoryLimit);
  // Photons in path order: each chunk's at its offset, copied in parallel, each chunk freed once copied.
  std::vector<size_t> offset(chunks + 1, 0);
  for (size_t c = 0; c < chunks; ++c) offset[c + 1] = offset[c] + parts[c].size();
  std::vector<Photon> photons(total);
  tbb::parallel_for(size_t(0), chunks, [&](size_t c) {
    std::copy(parts[c].begin(), parts[c].end(), photons.begin() + long(offset[c]));
    std::vector<Photon>().swap(parts[c]);
  });
  return photons;
}

}  // namespace kasha
