#pragma once
// The photon-mapping estimate at a camera vertex (docs/photon-mapping.md §3): the photons of the
// pass within the gather radius, turned into reflected radiance for every lane of the camera path.
#include <memory>

#include "integrators/integrator.h"
#include "integrators/photon_mapping/photon_map.h"
#include "integrators/sensor_shares.h"

namespace kasha {

// What beginPass prepares for one iteration of Knaus & Zwicker: the photon map and its radii.
struct PhotonPass final : PassData {
  PhotonPass(std::vector<Photon> photons, float r, float h, size_t paths)
      : map(std::move(photons)), radius(r), bandwidth(h), density(1.0f / (kPi * r * r * float(paths))) {}
  PhotonMap map;
  float radius, bandwidth;
  float density;  // 1/(π r² N): turns a sum of f·Φ_p into reflected radiance
};

// Adds the photons within the pass's radius of p to `L`, camera lane k's share being
// T_k·Σ_p Σ_l f(λ_pl → λ_k)·Φ_pl/(π r² N) over the photons' lanes l, for the camera vertex whose Bsdf is `bsdf` (outgoing
// direction wo towards the camera) behind `bounces` specular vertices; photons whose subpath
// would make the path longer than maxDepth are skipped. The fluorescent lobe is exact for any pair
// of wavelengths. The elastic lobe counts photons from vertex elasticFromDepth of their subpath on
// (2 where next-event estimation covers direct light), through the wavelength kernel of the pass, or with
// `exactElastic` (the first vertex, where nothing depends on the camera's wavelengths) straight to
// the sensor at each photon lane's own wavelength, added to `xyz`.
void gatherPhotons(const PhotonPass& pass, const Bsdf& bsdf, const Vec3& p, const Vec3& wo, const CameraLanes& lanes,
                   int bounces, int maxDepth, int elasticFromDepth, bool exactElastic, SampleContext& ctx, SensorShares& L, Vec3& xyz);

}  // namespace kasha
