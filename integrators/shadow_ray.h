#pragma once
// The shadow ray of next-event estimation: is the light point of `ls` visible from the surface hit?
#include <cmath>

#include "core/light.h"
#include "scene/scene.h"
#include "integrators/integrator.h"

namespace kasha {

inline bool lightVisible(const Scene& scene, const Hit& hit, const LightSample& ls, RayCounter& counter) {
  const Vec3 origin = offsetPoint(hit.p, hit.ng, ls.wi);
  const float tMax = std::isinf(ls.dist) ? kInf : ls.dist * (1.0f - 1e-4f) - rayEpsilon(hit.p);
  ++counter.shadow;
  return !scene.accel->occluded(origin, ls.wi, tMax);
}

}  // namespace kasha
