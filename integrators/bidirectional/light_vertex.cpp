#include "integrators/bidirectional/light_vertex.h"

#include <algorithm>

#include "integrators/bidirectional/connect_parts.h"
#include "integrators/bidirectional/path_media.h"

namespace kasha::bidir {

void keepLightVertices(const std::vector<PathVertex>& L, bool own, const Scene& scene, const Strategies& st,
                       std::vector<LightVertex>& out) {
  for (size_t m = 1; m < L.size(); ++m) {
    const PathVertex& v = L[m];
    const PathVertex& prev = L[m - 1];
    const float* beta = v.lanesEndHere ? v.betaArriving : v.beta;
    if (!mergeable(v, true) || std::none_of(beta, beta + kLightVertexLanes, [](float b) { return b > 0.0f; })) continue;
    LightVertex r{};
    std::copy(&v.p.x, &v.p.x + 3, r.p);
    const Vec3 wi = v.bsdf->toLocal(towards(v, prev));
    std::copy(&wi.x, &wi.x + 3, r.wi);
    // Where the lanes end here, a merge still takes the light of every lane that arrived.
    std::copy(beta, beta + kLightVertexLanes, r.beta);
    r.lambda = v.lambda;
    r.lambda0 = L[0].lambda;
    r.ownStart = own ? L[0].choicePdf : 0.0f;
    r.pdfFwd = v.pdfFwd;
    r.pdfPrev = prev.pdfFwd;
    r.prevGeometry = float(toArea(scene, 1.0f, v, prev) * flightFactor(scene, TransportMode::Radiance, v.arrival, prev, v.lambda));
    r.sums = lightMultiplicity(L, int(m) - 1, st, false, false) + v.sums;
    r.light = int16_t(L[0].light);
    r.depth = uint8_t(m);
    r.lane = v.lanesEndHere ? int8_t(-1) : v.lane;
    r.flags = uint8_t((own ? LightVertex::kOwn : 0) | (v.elasticBefore ? LightVertex::kElasticBefore : 0) |
                      (v.lanesKept ? LightVertex::kLanesKept : 0) | (prev.joinable(false) ? LightVertex::kPrevConnectible : 0) |
                      (prev.lobe == SpectralLobe::Fluorescent ? LightVertex::kPrevFluorescent : 0) |
                      (L[0].kind == Kind::Light ? LightVertex::kFiniteLight : 0) |
                      (v.inMedium() ? LightVertex::kMedium : 0) | (v.lightBeam > 0.0f ? LightVertex::kLightBeam : 0));
    out.push_back(r);
  }
}

}  // namespace kasha::bidir
