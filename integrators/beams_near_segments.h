#pragma once
// Segments near a ray segment, the query of photon beams against a query beam (Jarosz et al. 2011;
// docs/media-beams.md): which of a set of segments (the beams) come within radius r of the query
// segment. The beams are capsules of radius r, an Embree user geometry in a scene of their own whose
// intersect function tests the distance of the two segments, and a query is one Embree ray through
// their bounds that records every capsule the segment comes into (segment_hits.h), also one that
// holds it whole (Embree's round curves report no hit from inside, nor answer point queries).
#include <embree3/rtcore.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "core/math.h"

namespace kasha {

class BeamsNearSegments {
 public:
  struct Beam {
    Vec3 a{0.0f}, w{0.0f};  // from a, in direction w (unit)
    float length = 0.0f;
  };

  BeamsNearSegments(const std::vector<Beam>& beams, float radius);
  ~BeamsNearSegments();
  BeamsNearSegments(const BeamsNearSegments&) = delete;
  BeamsNearSegments& operator=(const BeamsNearSegments&) = delete;

  // The beams whose capsule of radius r the segment o + t·d (d of unit length), t in [0, length],
  // meets, in increasing index: every beam closer than r to it is among them. `found` belongs to the
  // caller and is overwritten.
  void near(const Vec3& o, const Vec3& d, float length, std::vector<uint32_t>& found) const;
  float radius() const { return radius_; }
  struct Shared;  // what Embree's callbacks read: the beams and the radius

 private:
  std::vector<Beam> beams_;
  float radius_;
  std::unique_ptr<Shared> user_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

}  // namespace kasha
