#include "integrators/bidirectional/light_vertex_pass.h"

#include "integrators/chunked_paths.h"
#include "integrators/point_map_impl.h"

namespace kasha {

template class PointMap<bidir::LightVertex>;

std::vector<bidir::LightVertex> traceLightVertices(const Scene& scene, const bidir::Lanes& lanes,
                                                  const bidir::WalkSettings& ws, const LightVertexTracing& t,
                                                  uint64_t seed, RayCounter& counter) {
  using namespace bidir;
  return traceInChunks<LightVertex>(t.paths, t.memoryLimit, kBytesPerLightVertex,
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
                                    });
}

}  // namespace kasha
