#pragma once
// The photon-mapping estimate at a camera vertex (docs/photon-mapping.md §3, §9): the photons of the
// pass within the gather radius, turned into reflected (at a surface) or in-scattered (in a medium)
// radiance for every lane of the camera path.
#include <memory>

#include "integrators/integrator.h"
#include "integrators/photon_mapping/photon_map.h"
#include "integrators/photon_mapping/photon_tracer.h"
#include "integrators/sensor_shares.h"

namespace kasha {

// A photon map with the kernel of one pass: its radius and 1/(V N), V the kernel's volume (π r² for
// a disc on surfaces, (4/3)π r³ for a ball in media) and N the subpaths of the pass, which turns a
// sum of f·Φ_p into radiance (docs/photon-mapping.md §3, §9).
struct KernelPhotons {
  KernelPhotons(std::vector<Photon> photons, float r, float kernelVolume, size_t paths)
      : map(std::move(photons)), radius(r), density(1.0f / (kernelVolume * float(paths))) {}
  PhotonMap map;
  float radius;
  float density;
};

// What beginPass prepares for one iteration of Knaus & Zwicker: the surface photons with their
// discs, the volume photons with their balls, and the elastic wavelength kernel's half-width.
struct PhotonPass final : PassData {
  PhotonPass(PassPhotons photons, float r, float rVolume, float h, size_t paths)
      : surface(std::move(photons.surface), r, kPi * r * r, paths),
        volume(std::move(photons.volume), rVolume, (4.0f / 3.0f) * kPi * rVolume * rVolume * rVolume, paths),
        bandwidth(h) {}
  KernelPhotons surface, volume;
  float bandwidth;
};

// Adds the photons of `photons` within its radius of p to `L`, camera lane k's share being
// T_k·Σ_p Σ_l f(λ_pl → λ_k)·Φ_pl·density over the photons' lanes l, for the camera vertex whose
// Bsdf is `bsdf` (outgoing direction wo towards the camera; a surface's with the surface photons,
// a medium's with the volume photons) behind `bounces` vertices; photons whose subpath
// would make the path longer than maxDepth are skipped. The fluorescent lobe is exact for any pair
// of wavelengths. The elastic lobe counts photons from vertex elasticFromDepth of their subpath on
// (2 where next-event estimation covers direct light), through the wavelength kernel of half-width
// `bandwidth`, or with `exactElastic` (where nothing on the camera path depends on its
// wavelengths) straight to the sensor at each photon lane's own wavelength, added to `xyz`.
void gatherPhotons(const KernelPhotons& photons, float bandwidth, const Bsdf& bsdf, const Vec3& p, const Vec3& wo,
                   const CameraLanes& lanes, int bounces, int maxDepth, int elasticFromDepth, bool exactElastic,
                   SampleContext& ctx, SensorShares& L, Vec3& xyz);

}  // namespace kasha
