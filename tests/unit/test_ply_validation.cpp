// The PLY check before assimp (core/ply_validation.h) and readPlyMesh behind it: valid ASCII and
// binary files of both byte orders pass, rewritten canonically, and read the same triangles; every
// hostile file of issue 36 (a truncated binary body, faces of fewer than 3 or out-of-range
// indices, a header cut short, counts far beyond the file's size or the memory limit, ASCII with
// fewer lines than declared) is an InputError or MemoryLimitError naming the file and the field.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/memory_budget.h"
#include "core/mesh_builders.h"
#include "core/ply_validation.h"
#include "tests/expect_contains.h"
#include "tests/ply_files.h"

namespace kasha {
namespace {

constexpr uint64_t kLimit = uint64_t(1) << 30;

// The message validatePly throws for `bytes`, or "" if it accepts them.
std::string problem(const std::string& bytes, uint64_t memoryLimit = kLimit) {
  try {
    validatePly(bytes, "m.ply", memoryLimit);
  } catch (const std::runtime_error& e) {  // InputError, MemoryLimitError
    return e.what();
  }
  return "";
}

using test::asciiPlyTetrahedron;
using test::binaryPlyTetrahedron;
using test::kPlyAsciiFaces;
using test::kPlyAsciiVertices;
using test::kPlyVertices;
using test::plyHeader;
using Binary = test::PlyBinary;

TEST(PlyValidation, ValidFilesAreRewrittenCanonically) {
  // Comments, CRLF, tabs, a '+', exponents and blank lines: what assimp reads is plain.
  const std::string ascii =
      "ply\r\nformat ascii 1.0\r\ncomment by hand\r\nelement vertex 4\r\nproperty float x\r\nobj_info mid-element\r\n"
      "property float32 y\r\nproperty float z\r\nelement face 4\r\nproperty list uint8 int32 vertex_indices\r\nend_header\r\n"
      "0 0 0\r\n\r\n+1.0 0 0\r\n0\t1e0 0\r\n  0 0 1.\r\n3 0 2 1\r\n3 0 1 3\r\n3 0 3 2\r\n3 1 2 +3\r\n\r\n";
  EXPECT_EQ(validatePly(ascii, "m.ply", kLimit), plyHeader("ascii", 4, 4) + kPlyAsciiVertices + kPlyAsciiFaces);
  // Binary data passes untouched behind a canonical header that ends "\r\n" (below).
  for (const bool be : {false, true}) {
    const std::string file = binaryPlyTetrahedron(be);
    const std::string out = validatePly(file, "m.ply", kLimit);
    const size_t data = file.find("end_header\n") + 11;
    EXPECT_EQ(out, file.substr(0, data - 1) + "\r\n" + file.substr(data)) << be;
  }
}

TEST(PlyValidation, HeaderMustBeCompleteAndWellFormed) {
  // Cut short, assimp 5.2 looped forever.
  EXPECT_EQ(problem("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"),
            "m.ply: header: the file ends before an 'end_header' line");
  EXPECT_EQ(problem("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_hea"),
            "m.ply: header: the file ends before an 'end_header' line");
  std::string comments = "ply\nformat ascii 1.0\n";
  while (comments.size() < (70u << 10)) comments += "comment padding padding padding padding\n";
  EXPECT_EQ(problem(comments + "end_header\n"), "m.ply: header: no 'end_header' line within its first 64 KiB");
  EXPECT_EQ(problem(""), "m.ply: header line 1: is not 'ply': not a PLY file");
  EXPECT_EQ(problem("plyx\n"), "m.ply: header line 1: is not 'ply': not a PLY file");
  EXPECT_EQ(problem("ply\nformat binary 1.0\nend_header\n"),
            "m.ply: header line 2: unknown format 'binary' (ascii, binary_little_endian, binary_big_endian)");
  EXPECT_EQ(problem("ply\nformat ascii 2.0\nend_header\n"), "m.ply: header line 2: unknown version '2.0' (1.0)");
  EXPECT_EQ(problem("ply\nelement vertex 1\n"),
            "m.ply: header line 2: expected 'format ascii 1.0' (or binary_little_endian, binary_big_endian)");
  // Each after "ply" and "format ascii 1.0".
  const std::string fmt = "ply\nformat ascii 1.0\n";
  const std::pair<std::string, std::string> lines[] = {
      {"element vertex 1\nproperty float128 x\nend_header\n",
       "m.ply: header line 4: unknown type 'float128' (char, uchar, short, ushort, int, uint, float, double)"},
      {"element face 1\nproperty list float int vertex_indices\nend_header\n",
       "m.ply: header line 4: a list's count must have an integer type, not 'float'"},
      {"element face 1\nproperty list uchar vertex_indices\nend_header\n",
       "m.ply: header line 4: expected 'property TYPE NAME' or 'property list COUNT_TYPE ITEM_TYPE NAME'"},
      {"property float x\n",
       "m.ply: header line 3: a property before the first element"},
      {"element vertex 1\nproperty float x\nproperty float x\n",
       "m.ply: header line 5: element 'vertex' has a second property 'x'"},
      {"element vertex 1\nproperty float x\nelement vertex 2\n",
       "m.ply: header line 5: a second element 'vertex'"},
      {"element vertex -1\n",
       "m.ply: header line 3: element 'vertex': count '-1' is not an integer from 0 to 4294967295"},
      {"element vertex 4294967296\n",
       "m.ply: header line 3: element 'vertex': count '4294967296' is not an integer from 0 to 4294967295"},
      {"element tristrips 1\n",
       "m.ply: header line 3: element 'tristrips' (triangle strips) is not supported: write faces"},
      {"element TextureFile 1\n",
       "m.ply: header line 3: element 'TextureFile' is not supported"},
      {"elements vertex 1\n",
       "m.ply: header line 3: unknown keyword 'elements' (element, property, comment, obj_info, end_header)"},
      {"comment a\x1b[2Jb\n",
       "m.ply: header line 3: holds the byte '\\x1b'"},
      {"comment caf\xc3\xa9\nelement caf\xc3\xa9 1\n",
       "m.ply: header line 4: holds the byte '\\xc3' (names and numbers are ASCII)"},
      {"end_header x\n",
       "m.ply: header line 3: 'end_header' is followed by 'x'"},
  };
  for (const auto& [text, message] : lines) EXPECT_EQ(problem(fmt + text), message);
  // What kasha reads.
  EXPECT_EQ(problem(fmt + "element face 0\nproperty list uchar int vertex_indices\nend_header\n"),
            "m.ply: header: no element vertex");
  EXPECT_EQ(problem(fmt + "element vertex 0\nproperty float x\nproperty float y\nend_header\n"),
            "m.ply: element vertex: has no property z");
  EXPECT_EQ(problem(fmt + "element vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n"),
            "m.ply: header: no element face (a mesh needs faces)");
  EXPECT_EQ(problem(plyHeader("ascii", 1, 0) + "0 0 0\n"), "m.ply: element face: declares no faces");
  EXPECT_EQ(problem(fmt + "element face 0\nproperty list uchar int vertex_indices\nelement vertex 0\n"
                          "property float x\nproperty float y\nproperty float z\nend_header\n"),
            "m.ply: element face: comes before element vertex");
  EXPECT_EQ(problem(fmt + "element vertex 0\nproperty float x\nproperty float y\nproperty float z\nelement face 0\n"
                          "property list uchar int corners\nend_header\n"),
            "m.ply: element face: has no list property vertex_indices");
  EXPECT_EQ(problem(plyHeader("ascii", 0, 0).insert(plyHeader("ascii", 0, 0).find("end_header"), "element empty 0\n")),
            "m.ply: element empty: has no properties");
  EXPECT_EQ(problem(plyHeader("ascii", 0, 0, "property int vertex_index\n")),
            "m.ply: element face: property vertex_index must be a list of integers");
}

TEST(PlyValidation, CountsAreCheckedAgainstTheFileSizeBeforeTheData) {
  // About 200 bytes declaring 3·10⁸ vertices: assimp 5.2 allocated them (4 GB) before refusing.
  const std::string huge = plyHeader("binary_little_endian", 300000000, 1) + std::string(40, '\0');
  EXPECT_EQ(problem(huge),
            "m.ply: element vertex: 300000000 declared need at least 3.35 GiB of data with the elements before them, "
            "but the file holds 40 bytes after its header (it is truncated, or the count is wrong)");
  EXPECT_CONTAINS(problem(plyHeader("ascii", 4, 4000000) + kPlyAsciiVertices + kPlyAsciiFaces),
                  "m.ply: element face: 4000000 declared need at least 7.63 MiB of data");
  // Consistent with the file's size but not with the memory limit: 600 faces of 13 bytes.
  Binary many;
  many.vertices();
  for (int i = 0; i < 600; ++i) many.face({0, 1, 2});
  const std::string file = plyHeader("binary_little_endian", 4, 600) + many.bytes;
  EXPECT_EQ(problem(file), "");
  EXPECT_EQ(problem(file, 64 << 10),
            "m.ply: reading its elements (4 vertex, 600 face) needs 120 KiB, more than the memory limit of 64.0 KiB "
            "(raise it with --memory-limit)");
}

TEST(PlyValidation, BinaryDataMustFillTheFileExactly) {
  const std::string file = binaryPlyTetrahedron(false);
  // Cut inside the last face (assimp 5.2 read past the end: SIGSEGV) and inside the vertices.
  EXPECT_EQ(problem(file.substr(0, file.size() - 7)), "m.ply: face 3: the file ends inside it (it is truncated)");
  Binary cut;
  cut.vertices();
  EXPECT_EQ(problem(plyHeader("binary_little_endian", 4, 1) + cut.bytes.substr(0, 30)),
            "m.ply: element vertex: 4 declared need at least 48 bytes of data with the elements before them, but the "
            "file holds 30 bytes after its header (it is truncated, or the count is wrong)");
  EXPECT_EQ(problem(file + "xyz"), "m.ply: data: 3 bytes follow the last element the header declares");
  // A negative list count (char), and one far beyond the file.
  Binary neg(true);
  neg.vertices().put(int8_t(-1));
  std::string h = plyHeader("binary_big_endian", 4, 1);
  EXPECT_EQ(problem(h.replace(h.find("list uchar"), 10, "list char") + neg.bytes),
            "m.ply: face 0: list vertex_indices has a negative count -1");
  Binary big(true);
  big.vertices().put(uint32_t(4000000000u)).put(int32_t(0)).put(int32_t(1)).put(int32_t(2));
  h = plyHeader("binary_big_endian", 4, 1);
  EXPECT_EQ(problem(h.replace(h.find("list uchar"), 10, "list uint") + big.bytes),
            "m.ply: face 0: the file ends inside it (it is truncated)");
}

TEST(PlyValidation, FacesNeedThreeIndicesOfExistingVertices) {
  for (const int n : {0, 1, 2}) {
    const std::vector<int> f(size_t(n), 0);
    Binary b;
    b.vertices().face({0, 1, 2}).face(f);
    const std::string why = "has " + std::to_string(n) + (n == 1 ? " vertex index" : " vertex indices") +
                            "; a face needs at least 3";
    EXPECT_EQ(problem(plyHeader("binary_little_endian", 4, 2) + b.bytes), "m.ply: face 1: " + why);
    const std::string line = std::vector<std::string>{"0", "1 0", "2 0 0"}[size_t(n)];
    EXPECT_EQ(problem(plyHeader("ascii", 4, 2) + kPlyAsciiVertices + "3 0 1 2\n" + line + "\n"), "m.ply:15: face 1: " + why);
  }
  Binary out;
  out.vertices().face({0, 1, 4});
  EXPECT_EQ(problem(plyHeader("binary_little_endian", 4, 1) + out.bytes),
            "m.ply: face 0: vertex index 4 is not below the number of vertices, 4");
  EXPECT_EQ(problem(plyHeader("ascii", 4, 1) + kPlyAsciiVertices + "3 0 -1 2\n"),
            "m.ply:14: face 0: vertex index -1 is not below the number of vertices, 4");
  // A face's texture coordinates are two a corner (assimp 5.2 indexed past the face otherwise).
  const std::string uv = plyHeader("ascii", 4, 1, "property list uchar float texcoord\n") + kPlyAsciiVertices;
  EXPECT_EQ(problem(uv + "3 0 1 2 6 0 0 1 0 0 1\n"), "");
  EXPECT_EQ(problem(uv + "3 0 1 2 8 0 0 1 0 0 1 1 1\n"), "m.ply:15: face 0: texcoord holds 8 numbers for 3 corners (two a corner)");
}

TEST(PlyValidation, AsciiElementsAreOneLineOfNumbersEach) {
  // Fewer vertex lines than declared: assimp 5.2 read the faces as vertices and rendered.
  EXPECT_EQ(problem(plyHeader("ascii", 5, 4) + kPlyAsciiVertices + kPlyAsciiFaces),
            "m.ply:14: vertex 4: has 4 numbers, more than its properties take (3)");
  // Blank lines pass the size bound (bytes) but do not count as elements.
  EXPECT_EQ(problem(plyHeader("ascii", 5, 1) + kPlyAsciiVertices + std::string(10, '\n')),
            "m.ply: element vertex: the file ends after 4 of its 5 lines");
  EXPECT_EQ(problem(plyHeader("ascii", 4, 5) + kPlyAsciiVertices + kPlyAsciiFaces),
            "m.ply: element face: the file ends after 4 of its 5 lines");
  EXPECT_EQ(problem(plyHeader("ascii", 4, 4) + kPlyAsciiVertices + kPlyAsciiFaces + "3 0 1 2\n"),
            "m.ply:18: data: a line after the last element the header declares");
  const std::string h = plyHeader("ascii", 1, 1);
  EXPECT_EQ(problem(h + "0.5 0.25\n"), "m.ply:10: vertex 0: the line ends after 2 numbers; element vertex needs more");
  EXPECT_EQ(problem(h + "0 0 nan\n"), "m.ply:10: vertex 0: 'nan' is not a finite number (float)");
  EXPECT_EQ(problem(h + "0 0 1e39\n"), "m.ply:10: vertex 0: '1e39' is not a finite number (float)");
  EXPECT_EQ(problem(h + "0 0 0x1p3\n"), "m.ply:10: vertex 0: '0x1p3' is not a finite number (float)");
  EXPECT_EQ(problem(h + "0 0 1\f\n"), "m.ply:10: vertex 0: '1\\x0c' is not a finite number (float)");
  EXPECT_EQ(problem(h + "0 0 1\r2\n"), "m.ply:10: vertex 0: '1\\x0d2' is not a finite number (float)");
  EXPECT_EQ(problem(plyHeader("ascii", 4, 1) + kPlyAsciiVertices + "256 0 1 2\n"),
            "m.ply:14: face 0: '256' is not an integer from 0 to 255 (uchar)");
  EXPECT_EQ(problem(plyHeader("ascii", 4, 1) + kPlyAsciiVertices + "3 0 1 2.5\n"),
            "m.ply:14: face 0: '2.5' is not an integer from -2147483648 to 2147483647 (int)");
}

TEST(PlyValidation, ReadPlyMeshReadsWhatWasChecked) {
  // assimp 5.2 drops a first data byte 0x0A after "end_header\n" (taking it for the end of a
  // "\r\n"): x = 1.0000012 has that byte first in little-endian order.
  Binary lf;
  float x;
  const uint32_t bits = 0x3f80000au;
  std::memcpy(&x, &bits, 4);
  lf.put(x).put(0.0f).put(0.0f);
  for (int v = 1; v < 4; ++v) lf.put(kPlyVertices[v][0]).put(kPlyVertices[v][1]).put(kPlyVertices[v][2]);
  lf.faces();
  ASSERT_EQ(lf.bytes[0], '\n');
  Shape s;
  readPlyMesh(plyHeader("binary_little_endian", 4, 4) + lf.bytes, "m.ply", kLimit, s);
  ASSERT_EQ(s.positions.size(), 4u);
  EXPECT_EQ(s.positions[0].x, x);
  EXPECT_EQ(s.positions[3].z, 1.0f);
  const std::vector<uint32_t> indices = s.indices;
  EXPECT_EQ(indices.size(), 12u);
  // ASCII, and both byte orders, give the same triangles.
  for (const std::string& file : {asciiPlyTetrahedron(), binaryPlyTetrahedron(false),
                                  binaryPlyTetrahedron(true)}) {
    Shape t;
    readPlyMesh(file, "m.ply", kLimit, t);
    ASSERT_EQ(t.positions.size(), 4u);
    for (int v = 0; v < 4; ++v)
      for (int k = 0; k < 3; ++k) EXPECT_EQ(t.positions[size_t(v)][k], kPlyVertices[v][k]);
    EXPECT_EQ(t.indices, indices);
  }
  // Other elements are checked and left out: assimp 5.2 reads their data as the next element's
  // (a fuzzing finding: an element "camera" between the vertices and the faces gave faces of
  // garbage indices).
  const std::string camera = "element camera 2\nproperty float px\nproperty list uchar int ids\n";
  std::string ascii = plyHeader("ascii", 4, 4);
  ascii.insert(ascii.find("element face"), camera);
  ascii = ascii + kPlyAsciiVertices + "5 0\n-1.25 2 7 7\n" + kPlyAsciiFaces;
  EXPECT_EQ(validatePly(ascii, "m.ply", kLimit), asciiPlyTetrahedron());
  std::string binary = plyHeader("binary_big_endian", 4, 4);
  binary.insert(binary.find("element face"), camera);
  Binary data(true);
  data.vertices().put(5.0f).put(uint8_t(0)).put(-1.25f).put(uint8_t(2)).put(int32_t(7)).put(int32_t(7)).faces();
  for (const std::string& file : {ascii, binary + data.bytes}) {
    Shape t;
    readPlyMesh(file, "m.ply", kLimit, t);
    EXPECT_EQ(t.indices, indices);
  }
  EXPECT_EQ(problem(ascii.replace(ascii.find("-1.25 2 7 7"), 11, "-1.25 2 7")),
            "m.ply:18: camera 1: the line ends after 3 numbers; element camera needs more");
  Shape refused;
  EXPECT_THROW(readPlyMesh(plyHeader("ascii", 5, 4) + kPlyAsciiVertices + kPlyAsciiFaces, "m.ply", kLimit, refused), InputError);
  EXPECT_TRUE(refused.positions.empty());
}

}  // namespace
}  // namespace kasha
