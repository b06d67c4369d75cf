#pragma once
// Every primitive of an Embree scene that a ray segment meets, not only the first: the query of
// kernels laid around points or beams (points_near_segments.h). A geometry takes part through
// collectEveryHit, an intersection filter that records each hit and rejects it, so that Embree's
// traversal goes on to the next.
#include <embree3/rtcore.h>

#include <cstdint>
#include <vector>

#include "core/math.h"

namespace kasha {

// Makes geometry g's hits recorded by hitsAlong (before rtcCommitGeometry).
void collectEveryHit(RTCGeometry g);

// For a user geometry's intersect function: records primitive `prim` as met by the hitsAlong query
// whose context it was handed (and reports no hit, so that traversal goes on).
void recordMet(RTCIntersectContext* context, uint32_t prim);

// Appends to `met` the primitive IDs of every collecting geometry's primitives that the segment
// o + t·d, t in [0, length], meets (a primitive met twice, as a sphere entered and left, twice).
void hitsAlong(RTCScene scene, const Vec3& o, const Vec3& d, float length, std::vector<uint32_t>& met);

}  // namespace kasha
