#pragma once
// A strict check of a PLY file before assimp (5.2) parses it. assimp's PLY reader trusts the file:
// it allocates what the header declares before reading a byte of data (a 200-byte file declaring
// 3·10⁸ vertices took 4 GB), reads past the end of a truncated binary body, asserts on a face of
// no vertices, writes texture coordinates through a face's indices unchecked and loops forever on
// a header without "end_header". This pass refuses all of that from the bytes alone, allocating
// nothing that depends on the declared counts, and checks:
// - the header: "ply", "format ascii|binary_little_endian|binary_big_endian 1.0", then "element
//   NAME COUNT" (COUNT < 2³²; each name once; no "tristrips" or "TextureFile", which assimp reads
//   wrongly) each with at least one "property TYPE NAME" or "property list COUNT_TYPE ITEM_TYPE
//   NAME" (each name once per element), "comment" and "obj_info" lines, and "end_header", all
//   within 64 KiB;
//   TYPE one of char uchar short ushort int uint float double (or int8 … float64), list counts of
//   an integer type; lines end in "\n" or "\r\n" and hold no other control characters, and no
//   bytes beyond ASCII outside comments;
// - what kasha reads: an element "vertex" with scalar x, y and z, and after it an element "face"
//   of at least one face with one list "vertex_indices" (or "vertex_index") of integers; a face
//   "texcoord" list holds two numbers per corner;
// - the counts against the file's size before anything else: every element needs at least a
//   number of bytes (binary: its scalars and list counts; ASCII: two bytes a scalar or list count),
//   and against the memory limit (about what assimp, kasha and Embree hold per element);
// - the data, streamed: binary elements fill the file exactly; ASCII elements are one line each,
//   blank lines aside, with one number per scalar and a list's count followed by that many items,
//   integers in their type's range and other numbers finite; every face has at least 3 indices,
//   each below the number of vertices.
// - mesh attributes, when asked for (Mitsuba 3's PLY naming; docs/scene-format.md): "vertex_NAME"
//   or "face_NAME" is the scalar properties NAME_x, NAME_y, NAME_z (or NAME_0, NAME_1, NAME_2, or
//   NAME_1, NAME_2, NAME_3) of the element vertex or face, or NAME_x (NAME_0, NAME_1) alone for one
//   channel; "…_P_color" is P_r, P_g, P_b (or P_r alone), and "…_color" also r, g, b or red,
//   green, blue. Float values are read as they are, integers as value/maximum of their type
//   decoded from sRGB (as Mitsuba); each must lie in [0, 1]. Face attributes need triangles.
// Errors are InputError "path: FIELD: reason" (ASCII data "path:LINE: FIELD: reason"), FIELD
// naming what is wrong ("header line 3", "element vertex", "face 17", elements counted from 0 as
// PLY's indices are), or MemoryLimitError.
#include <cstdint>
#include <string>
#include <vector>

#include "core/shape.h"

namespace kasha {

// The file as assimp must read it: its elements "vertex" and "face" alone (assimp 5.2 misreads
// any other), under a canonical header (single spaces, "\n", no comments, whose last line assimp
// reads correctly however the binary data begins), their data binary as it is or ASCII rewritten
// as one line of single-spaced numbers per element (integers in decimal, other numbers as the
// shortest decimal text of their value in the declared type), so what assimp parses is what was
// checked.
// attributes: the mesh attributes to read ("vertex_color", ...; an element without one is an
// error), returned in `read` in that order (MeshAttribute, core/shape.h), their memory counted
// with the mesh's.
std::string validatePly(const std::string& bytes, const std::string& path, uint64_t memoryLimit,
                        const std::vector<std::string>& attributes = {}, std::vector<MeshAttribute>* read = nullptr);

}  // namespace kasha
