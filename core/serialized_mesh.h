#pragma once
// Mitsuba's serialized meshes (`.serialized`, Mitsuba 3 docs: "Serialized mesh loader"): versions 3
// and 4 (Mitsuba 0.5/0.6, and the data files of Mitsuba 3's documentation) and 5 (what Mitsuba 3
// writes now). All numbers are little-endian. The file is a sequence of meshes, each
//   uint16 0x041C, uint16 version, then one zlib stream holding, in versions 3 and 4,
//     uint32 flags (0x0001 vertex normals, 0x0002 texture coordinates, 0x0008 vertex colours,
//            0x0010 face normals, 0x1000 single, 0x2000 double precision),
//     version 4 only: the mesh's name, UTF-8 ending in a NUL byte,
//     uint64 V (vertices), uint64 F (triangles),
//     3V positions, [3V normals], [2V texture coordinates], [3V colours] (floats, or doubles with
//     0x2000), 3F uint32 vertex indices;
//   and in version 5
//     uint32 flags (layout 0x0001 normals, 0x0002 tangents, 0x0004 texture coordinates; 0x0010 face
//            normals; 0x1000 single precision, required),
//     uint32 length and the bytes of the name, uint64 V, F, P (surface points), N (normal groups),
//     8V floats: per vertex its position, normal (with tangents: the shading frame as modified
//     Rodrigues parameters) and texture coordinates, 4F uint32: per face three vertex indices and
//     a BSDF index, [V uint32 indices < P], [V uint32 indices < N], uint32 A, and A custom
//     attributes (uint32 length and name, a flag byte, uint32 channels C in [1, 4], C floats per
//     face for names starting "face_", else per vertex), which kasha skips;
// and the file ends in a dictionary: one offset per mesh (uint32 in version 3, uint64 later) of
// where its header starts, then uint32 the number of meshes. Mesh 0 starts at offset 0 and is read
// without the dictionary, as Mitsuba does.
//
// The reader trusts nothing in the bytes: the dictionary is checked against the file's size, the
// counts against what the compressed bytes can hold (zlib inflates at most 1032:1) and against the
// memory limit before anything is allocated for them, the inflated output is bounded by the
// counts (a stream holding more or less than they declare is an error), every number is finite
// and every index below V.
#include <cstdint>
#include <string>

#include "core/shape.h"

namespace kasha {

// Appends mesh `shapeIndex` of a serialized file's bytes to s: positions, three indices per
// triangle, and per corner the stored normals (Shape::cornerNormals) and texture coordinates
// (Shape::cornerUvs; Mitsuba's (u, v) with v counted from the image's top row, so kasha's v, from
// the bottom, is 1 − v). Vertex colours, maps and attributes are read and dropped. Returns whether
// the file asks for face normals, which Mitsuba 3 honours in version 5 when the shape leaves
// `face_normals` unset (in versions 3 and 4 only the property counts: false). `path` names the
// file in messages. Throws InputError "path: FIELD: reason" (FIELD e.g. "header", "shape_index",
// "mesh 2: face 17") or MemoryLimitError.
bool readSerializedMesh(const std::string& bytes, const std::string& path, uint64_t shapeIndex,
                        uint64_t memoryLimit, Shape& s);

}  // namespace kasha
