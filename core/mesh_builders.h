#pragma once
// Triangle meshes besides OBJ files, and how the scene format places them: PLY files (read with
// assimp), a tessellated unit disk, affine transforms and flipped normals.
#include <glm/mat4x4.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "core/shape.h"

namespace kasha {

// Appends the triangles of a PLY file's bytes (ASCII or binary; polygons triangulated) to s:
// validatePly (core/ply_validation.h) checks them and assimp parses what it returns, from memory.
// `attributes` names the mesh attributes to read into s.attributes (s must then be empty): the
// validation reads their values, assimp keeps the file's vertices and (triangles only) faces in
// order. `path` names the file in messages. Throws InputError or MemoryLimitError (the
// validation) or std::runtime_error with the reason (not a mesh, a non-finite vertex).
void readPlyMesh(const std::string& bytes, const std::string& path, uint64_t memoryLimit, Shape& s,
                 const std::vector<std::string>& attributes = {});

// The unit disk in the plane z = 0, facing +z, as a fan of `segments` triangles inscribed in the
// circle (its area is segments/(2π)·sin(2π/segments) of π); texture coordinates u = radius,
// v = angle/2π, as Mitsuba's disk (Mitsuba 3 docs: disk; src/shapes/disk.cpp).
void tessellateUnitDisk(Shape& s, int segments);

// p ← M·p for every vertex (M affine, column-major glm); vertex normals by M's inverse transpose.
void transformMesh(Shape& s, const glm::mat4& m);

// Reverses every triangle's winding, so its geometric normal (b − a) × (c − a) flips.
void flipMeshNormals(Shape& s);

// v ← 1 − v for every corner's texture coordinates: an image's rows read from the other end.
void flipMeshTexCoords(Shape& s);

}  // namespace kasha
