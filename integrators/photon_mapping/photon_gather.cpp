#include "integrators/photon_mapping/photon_gather.h"

#include "integrators/progressive_schedule.h"

namespace kasha {

void gatherPhotons(const KernelPhotons& photons, float bandwidth, const Bsdf& bsdf, const Vec3& p, const Vec3& wo,
                   const CameraLanes& lanes, int bounces, int maxDepth, int elasticFromDepth, bool exactElastic,
                   SampleContext& ctx, SensorShares& L, Vec3& xyz) {
  float sum[kMaxLanes] = {};  // Σ f·Φ_p arriving at each lane's wavelength
  const bool fluorescent = bsdf.has(BsdfFlags::Fluorescent);
  for (const size_t i : photons.map.within(p, photons.radius)) {
    const Photon& ph = photons.map[i];
    if (int(ph.depth) + bounces > maxDepth) continue;
    const Vec3 wi(ph.wi[0], ph.wi[1], ph.wi[2]);  // in the photon's own surface frame (world in a medium)
    const bool elastic = int(ph.depth) >= elasticFromDepth;
    for (int l = 0; l < ph.lanes; ++l) {
      const float lambda = ph.lambda[l], power = ph.power[l];
      // Fluorescent lobe: exact for any pair of wavelengths (docs/transport.md §4).
      if (fluorescent)
        for (int k = 0; k < lanes.n; ++k)
          sum[k] +=
              bsdf.eval({TransportMode::Radiance, SpectralLobe::Fluorescent, lambda, lanes.lambda[k]}, wi, wo) * power;
      if (!elastic) continue;
      const float fe = bsdf.eval({TransportMode::Radiance, SpectralLobe::Elastic, lambda, lambda}, wi, wo) * power;
      if (fe <= 0.0f) continue;
      if (exactElastic) {
        xyz += sensorResponse(ctx, lambda, fe * photons.density);  // the sensor at the lane's own wavelength
        continue;
      }
      for (int k = 0; k < lanes.n; ++k) sum[k] += fe * wavelengthKernel(lambda - lanes.lambda[k], bandwidth);
    }
  }
  for (int k = 0; k < lanes.n; ++k)
    if (sum[k] > 0.0f) L += lanes.beta[k] * (sum[k] * photons.density);
}

}  // namespace kasha
