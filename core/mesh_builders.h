#pragma once
// Triangle meshes besides OBJ files, and how the scene format places them: PLY files (read with
// assimp), a tessellated unit disk, affine transforms and flipped normals.
#include <glm/mat4x4.hpp>

#include <string>

#include "core/shape.h"

namespace kasha {

// Appends the triangles of a PLY file (ASCII or binary; polygons triangulated) to s. Throws
// std::runtime_error with the reason (unreadable, not a mesh, a non-finite vertex).
void readPlyMesh(const std::string& path, Shape& s);

// The unit disk in the plane z = 0, facing +z, as a fan of `segments` triangles inscribed in the
// circle (its area is segments/(2π)·sin(2π/segments) of π); texture coordinates u = angle/2π,
// v = radius, as Mitsuba's disk.
void tessellateUnitDisk(Shape& s, int segments);

// p ← M·p for every vertex (M affine, column-major glm).
void transformMesh(Shape& s, const glm::mat4& m);

// Reverses every triangle's winding, so its geometric normal (b − a) × (c − a) flips.
void flipMeshNormals(Shape& s);

}  // namespace kasha
