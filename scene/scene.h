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
#include "core/pixel_filter.h"
#include "core/shape.h"
#include "materials/material.h"
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
  std::unique_ptr<Accel> accel;
  std::unique_ptr<LightSelector> lightSelector;

  // Texture coordinates of a hit (Shape::surfaceUv).
  Vec2 uv(const Hit& h) const { return shapes[h.shape].surfaceUv(h.prim, h.bary, h.ng); }
  // The scattering function at a hit for a path carrying `wavelengths` there (Material::bsdf; its
  // textures read the hit's texture coordinates and mesh attributes), in the shading frame of the mesh's vertex normals if it has them (Shape::shadingNormal).
  Bsdf bsdf(const Hit& h, std::span<const float> wavelengths) const {
    const Shape& s = shapes[h.shape];
    const Material& m = *materials[s.material];
    const Frame geometric = Frame::fromNormal(h.ng);
    const Frame shading = s.cornerNormals.empty() ? geometric : Frame::fromNormal(s.shadingNormal(h.prim, h.bary, h.ng));
    return m.bsdf(HitContext{m.textured() ? uv(h) : Vec2(0.0f), geometric, shading, wavelengths, MeshPoint{&s, h.prim, h.bary}});
  }
  const EnvironmentLight* environment() const {
    return environmentLight < 0 ? nullptr : static_cast<const EnvironmentLight*>(lights[size_t(environmentLight)].get());
  }
};

}  // namespace kasha
