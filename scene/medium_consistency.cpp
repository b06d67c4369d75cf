#include "scene/medium_consistency.h"

#include "core/error.h"

namespace kasha {
namespace {

// Rays per side of the image, and crossings followed per ray.
constexpr int kProbeRays = 32;
constexpr int kMaxCrossings = 256;

std::string mediumName(const Scene& scene, int m) { return m < 0 ? "vacuum" : "medium '" + scene.media[size_t(m)]->name() + "'"; }

}  // namespace

void checkMediumAssignments(const Scene& scene, const std::string& file) {
  if (!scene.hasMedia()) return;
  for (int py = 0; py < kProbeRays; ++py)
    for (int px = 0; px < kProbeRays; ++px) {
      const Vec2 film((float(px) + 0.5f) / kProbeRays * float(scene.camera.width()),
                      (float(py) + 0.5f) / kProbeRays * float(scene.camera.height()));
      Ray ray = scene.camera.generateRay(film, Vec2(0.5f));
      int medium = scene.cameraMedium;
      int previous = -1;  // the shape crossed before, for the message
      for (int crossing = 0; crossing < kMaxCrossings; ++crossing) {
        const std::optional<Hit> hit = scene.accel->intersect(ray);
        if (!hit) break;
        const Shape& shape = scene.shapes[hit->shape];
        if (shape.media) {
          const bool entering = glm::dot(ray.d, hit->ng) < 0.0f;
          const int expected = entering ? shape.media->exterior : shape.media->interior;
          if (medium != expected) {
            const std::string after =
                previous < 0 ? (crossing == 0 ? " (the camera's medium)" : "")
                             : " (after crossing shape '" + scene.shapes[size_t(previous)].name + "')";
            throw InputError(file, crossing == 0 && previous < 0 ? "/camera/medium" : "/shapes/" + std::to_string(hit->shape),
                             "a ray from the camera reaches shape '" + shape.name + "' in " + mediumName(scene, medium) +
                                 after + ", but its " + (entering ? "exterior" : "interior") + " is " +
                                 mediumName(scene, expected) +
                                 ": media overlap or their assignments disagree (docs/media.md §1)");
          }
          medium = entering ? shape.media->interior : shape.media->exterior;
          previous = int(hit->shape);
        }
        ray.o = offsetPoint(hit->p, hit->ng, ray.d);
      }
    }
}

}  // namespace kasha
