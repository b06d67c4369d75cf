#pragma once
// Scene geometry: triangle meshes (OBJ, PLY and serialized files, rectangles, disks), spheres and
// open cylinders, each with a material and optional area emission, and uniform-by-area point
// sampling for emissive shapes.
#include <glm/mat3x3.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/cylinder.h"
#include "core/ray.h"
#include "core/spectrum.h"

namespace kasha {

struct AreaEmission {
  Spectrum radiance;  // L_e(λ), W·m⁻²·sr⁻¹·nm⁻¹ up to the scene's unit
  float scale = 1.0f;
  bool twoSided = false;  // else emits on the side of the geometric normal only
  bool emitsTowards(const Vec3& ng, const Vec3& wOut) const { return twoSided || glm::dot(ng, wOut) > 0.0f; }
  float eval(float lambda, const Vec3& ng, const Vec3& wOut) const {
    return emitsTowards(ng, wOut) ? scale * radiance(lambda) : 0.0f;
  }
};

struct SurfaceSample {
  Vec3 p, ng;
  float pdfArea = 0.0f;
};

// Values a mesh file gives per vertex or per triangle (PLY properties, named as Mitsuba 3 names
// them: "vertex_color", "face_color", ...; core/ply_validation.h), read by mesh_attribute textures
// (core/mesh_attribute_texture.h). Values lie in [0, 1].
struct MeshAttribute {
  std::string name;          // "vertex_…": one value per vertex; "face_…": one per triangle
  int channels = 3;          // 1 (stored in all three components) or 3
  std::vector<Vec3> values;  // parallel to positions (vertex) or to the triangles (face)
  bool perFace() const { return name.starts_with("face_"); }
};

// The material index of a shape that is only a boundary between media (index-matched: light
// crosses it unchanged, docs/media.md §1).
inline constexpr uint32_t kNoMaterial = 0xffffffffu;

// The media on the two sides of a shape's surface: indices into Scene::media, −1 for vacuum. The
// interior is the side the geometric normal points away from.
struct MediumInterface {
  int interior = -1, exterior = -1;
};

struct Shape {
  enum class Kind { Mesh, Sphere, Cylinder } kind = Kind::Mesh;
  std::string name;
  uint32_t material = 0;  // or kNoMaterial
  // Absent: crossing the surface does not change the medium a ray is in.
  std::optional<MediumInterface> media;
  bool isMediumBoundary() const { return material == kNoMaterial; }
  std::optional<AreaEmission> emission;
  // Mesh
  std::vector<Vec3> positions;
  std::vector<uint32_t> indices;  // three per triangle
  std::vector<float> triangleCdf;  // cumulative area, for sampling
  std::vector<Vec3> normals;       // unit geometric normal per triangle
  std::vector<Vec2> cornerUvs;     // texture coordinates, three per triangle (parallel to indices); empty: none
  std::vector<Vec3> cornerNormals; // vertex normals (OBJ vn), three per triangle (parallel to indices); empty: none
  std::vector<MeshAttribute> attributes;  // those its material's textures read
  // Sphere
  Vec3 center{0.0f};
  float radius = 0.0f;
  // The world directions of the sphere's own x, y and z axes (columns; orthonormal, possibly a
  // mirror image): its texture coordinates are those of its normal in this frame. Identity unless
  // placed by a transform.
  glm::mat3 sphereAxes{1.0f};
  // Cylinder
  Cylinder cylinder;

  float area = 0.0f;

  // Precomputes areas; returns the number of zero-area triangles removed.
  size_t finalize();
  const Vec3& triangleNormal(uint32_t prim) const { return normals[prim]; }
  // Whether surfaceUv means anything: spheres and cylinders always, meshes when they were given
  // coordinates.
  bool hasUv() const { return kind != Kind::Mesh || !cornerUvs.empty(); }
  // Texture coordinates at a point. Triangles: the corners' coordinates interpolated with the
  // barycentrics (b1, b2) of corners 1 and 2. Spheres, from the outward normal n in the sphere's
  // own axes (sphereAxes): u = 1/2 + atan2(n_z, n_x)/(2π) (around +y), v = acos(−n_y)/π (0 at the
  // bottom, 1 at the top).
  // Cylinders, from their surface parameters (φ/2π, z/length) in bary: u = φ/2π, v = 1 − z/length,
  // Mitsuba's (u, v) with v counted from the image's bottom as kasha's textures count it.
  Vec2 surfaceUv(uint32_t prim, Vec2 bary, const Vec3& n) const;
  // ∂p/∂u and ∂p/∂v of surfaceUv's parameterisation at a point with outward normal n (spheres) on
  // triangle prim (meshes: constant over a triangle, PBR4 eq. 6.7's linear system in the corners'
  // differences; where the corners' uv are degenerate, or a mesh has none, an orthonormal pair
  // around the triangle's normal). Spheres: ∂p/∂u = 2πr·(−n_z, 0, n_x), ∂p/∂v = πr·(−n_y n_x/ρ, ρ,
  // −n_y n_z/ρ) with ρ = √(n_x² + n_z²), the derivatives of surfaceUv's angles, in the sphere's
  // own axes and turned into the world by them.
  // Cylinders (frame s, t, axis a): ∂p/∂u = 2πr·(cos φ·t − sin φ·s), ∂p/∂v = −length·a.
  struct UvDerivatives {
    Vec3 dpdu, dpdv;
  };
  UvDerivatives uvDerivatives(uint32_t prim, const Vec3& n) const;
  // The shading normal at a point with geometric normal ng (Hit::ng): the corners' normals
  // interpolated with the barycentrics and normalised (Phong shading), turned to ng's side of the
  // surface if it points away from it, so that both normals name the same side. ng itself for
  // spheres, meshes without normals, and where the interpolation is zero or not finite.
  Vec3 shadingNormal(uint32_t prim, Vec2 bary, const Vec3& ng) const;
  // The attribute of that name, or nullptr.
  const MeshAttribute* attribute(const std::string& name) const;
  // An attribute at a point: a vertex attribute's corner values interpolated with the
  // barycentrics (b1, b2) of corners 1 and 2, as surfaceUv; a face attribute's triangle value.
  Vec3 attributeAt(const MeshAttribute& a, uint32_t prim, Vec2 bary) const;
  SurfaceSample sampleUniform(Vec2 u) const;
  // Whether the surface encloses a volume: spheres; meshes without open edges; never an open cylinder.
  bool closed() const;
  // A mesh's edges (pairs of vertex positions) that are not shared by exactly two triangles.
  size_t openEdges() const;
};

}  // namespace kasha
