#include "integrators/bidirectional/light_vertex_pass.h"

#include "integrators/chunked_paths.h"
#include "integrators/point_map_impl.h"

namespace kasha {

template class PointMap<bidir::LightVertex>;

std::vector<bidir::LightVertex> traceLightVertices(const Scene& scene, const bidir::Lanes& lanes,
                                                  const bidir::WalkSettings& ws, const LightVertexTracing& t,
                                                  uint64_t seed, RayCounter& counter,
                                                  std::vector<bidir::PhotonBeam>* beams) {
  using namespace bidir;
  const bool keepBeams = beams && ws.strategies.merge.photonBeam > 0.0;
  std::vector<std::vector<PhotonBeam>> beamsOf(keepBeams ? t.paths : 0);  // per subpath, in subpath order
  std::vector<LightVertex> vertices = traceInChunks<LightVertex>(
      t.paths, t.memoryLimit, kBytesPerLightVertex,
      {"the light vertices of one vcm pass", "vertices", "render/vcm/photons_per_pass"}, counter,
      [&](size_t j, std::vector<LightVertex>& out, RayCounter& rays) {
        thread_local std::vector<PathVertex> LS, LO;
        Sampler rng(t.sampler, seed, 0, uint32_t(j));
        LS.clear(), LO.clear();
        if (ws.lightFirst) {
          traceMergedLightSubpath(scene, lanes, ws, rng, rays, LS, LO);
        } else {
          traceLightSubpath(scene, LightFamily::Shared, lanes, ws, rng, rays, LS);
          if (t.ownFamily) traceLightSubpath(scene, LightFamily::Own, lanes, ws, rng, rays, LO);
        }
        keepLightVertices(LS, false, scene, ws.strategies, out);
        keepLightVertices(LO, true, scene, ws.strategies, out);
        if (keepBeams) {
          keepPhotonBeams(LS, false, scene, ws.strategies, beamsOf[j]);
          keepPhotonBeams(LO, true, scene, ws.strategies, beamsOf[j]);
        }
      });
  if (keepBeams) {
    size_t count = 0;
    for (const std::vector<PhotonBeam>& b : beamsOf) count += b.size();
    const uint64_t used = saturatingMul(vertices.size(), kBytesPerLightVertex);
    requireMemory(saturatingMul(count, sizeof(PhotonBeam)) + used,
                  "the photon beams of one vcm pass (" + std::to_string(count) + " beams × " +
                      std::to_string(sizeof(PhotonBeam)) + " bytes, besides " + std::to_string(vertices.size()) +
                      " light vertices; lower render/vcm/photons_per_pass or set render/vcm/photon_beams to false)",
                  t.memoryLimit);
    beams->clear();
    beams->reserve(count);
    for (std::vector<PhotonBeam>& b : beamsOf) beams->insert(beams->end(), b.begin(), b.end());
  }
  return vertices;
}

}  // namespace kasha
