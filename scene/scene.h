#pragma once
// A loaded scene: immutable after loading; integrators only read it.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/accel.h"
#include "core/camera.h"
#include "core/light.h"
#include "core/medium.h"
#include "core/pixel_filter.h"
#include "core/shape.h"
#include "materials/material.h"
#include "materials/volume_scattering.h"
#include "scene/light_selector.h"
#include "scene/render_settings.h"

namespace kasha {

struct Scene {
  std::string path;  // the scene file
  WavelengthRange range;
  Camera camera;
  PixelFilter pixelFilter;  // the film's reconstruction filter (/camera/filter)
  RenderSettings render;
  std::vector<std::string> materialNames;
  std::vector<std::unique_ptr<Material>> materials;
  std::vector<Shape> shapes;
  std::vector<std::unique_ptr<Light>> lights;
  std::vector<int> shapeLight;        // index into lights per shape, or −1
  int environmentLight = -1;          // index into lights, or −1
  // Participating media (docs/media.md), their collision kernels (one per medium), the medium the
  // camera sits in and each light's (−1: vacuum). A light on a shape with a MediumInterface emits
  // into the medium on its emitting side.
  std::vector<std::unique_ptr<Medium>> media;
  std::vector<std::unique_ptr<VolumeScattering>> mediumScattering;
  int cameraMedium = -1;
  std::vector<int> lightMedium;  // parallel to lights
  std::unique_ptr<Accel> accel;
  std::unique_ptr<LightSelector> lightSelector;

  // Texture coordinates of a hit (Shape::surfaceUv).
  Vec2 uv(const Hit& h) const { return shapes[h.shape].surfaceUv(h.prim, h.bary, h.ng); }
  // The scattering function at a hit for a path carrying `wavelengths` there (Material::bsdf; its
  // textures read the hit's texture coordinates and mesh attributes), in the shading frame of the
  // mesh's vertex normals if it has them (Shape::shadingNormal); a textured material also gets the
  // texture coordinates' tangents (Shape::uvDerivatives).
  Bsdf bsdf(const Hit& h, std::span<const float> wavelengths) const {
    const Shape& s = shapes[h.shape];
    const Material& m = *materials[s.material];
    const Frame geometric = Frame::fromNormal(h.ng);
    const Frame shading = s.cornerNormals.empty() ? geometric : Frame::fromNormal(s.shadingNormal(h.prim, h.bary, h.ng));
    HitContext ctx{Vec2(0.0f), geometric, shading, wavelengths, MeshPoint{&s, h.prim, h.bary}};
    if (m.textured()) {
      ctx.uv = uv(h);
      const Shape::UvDerivatives d = s.uvDerivatives(h.prim, h.ng);
      ctx.dpdu = d.dpdu;
      ctx.dpdv = d.dpdv;
    }
    Bsdf b = m.bsdf(ctx);
    if (m.oneSided) b.restrictToFront();
    return b;
  }
  // Whether any ray can meet a medium or an index-matched boundary.
  bool hasMedia() const { return !media.empty(); }
  bool hasFluorescentMedia() const {
    for (const auto& m : media)
      if (m->fluoresces()) return true;
    return false;
  }
  // The medium a ray is in after leaving hit h along world direction d, having been in `current`:
  // the side of the shape's MediumInterface that d points into, or `current` if it has none.
  int mediumBeyond(const Hit& h, const Vec3& d, int current) const {
    const std::optional<MediumInterface>& m = shapes[h.shape].media;
    if (!m) return current;
    return glm::dot(d, h.ng) < 0.0f ? m->interior : m->exterior;
  }
  // The collision kernel of medium m at the collision x as a Bsdf (materials/volume_scattering.h),
  // in a fixed frame: a medium point has no normal, and its phase function depends on angles between
  // directions only. x matters only where the medium's albedo varies (media.md §7).
  // (Out of line, scene/scene.cpp: it stays out of the integrators' hot loops in scenes without media.)
  Bsdf mediumBsdf(int m, const Vec3& x) const;
  // The shape an emission sample of light l lies on (its MediumInterface names the medium on each
  // side): an area light's, whose samples alone have a normal; −1 for any other light.
  int emittingShape(const Light& l, const EmissionSample& es) const;
  const EnvironmentLight* environment() const {
    return environmentLight < 0 ? nullptr : static_cast<const EnvironmentLight*>(lights[size_t(environmentLight)].get());
  }
};

}  // namespace kasha
