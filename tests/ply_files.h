#pragma once
// PLY files built by the tests (tests/unit/test_ply_validation.cpp, tests/cli/test_cli_files.cpp):
// a header of x, y, z float vertices and uchar-counted int faces, a tetrahedron in ASCII and
// binary of either byte order, and a builder of binary data.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace kasha::test {

inline std::string plyHeader(const std::string& format, uint64_t vertices, uint64_t faces,
                             const std::string& faceExtra = "") {
  return "ply\nformat " + format + " 1.0\nelement vertex " + std::to_string(vertices) +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(faces) +
         "\nproperty list uchar int vertex_indices\n" + faceExtra + "end_header\n";
}

// A tetrahedron's vertices and faces (outward normals), and its ASCII data lines.
inline const float kPlyVertices[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
inline const std::vector<std::vector<int>> kPlyFaces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
inline const std::string kPlyAsciiVertices = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
inline const std::string kPlyAsciiFaces = "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

// Binary data: values appended in the chosen byte order.
struct PlyBinary {
  explicit PlyBinary(bool be = false) : bigEndian(be) {}
  bool bigEndian;
  std::string bytes;
  template <class T>
  PlyBinary& put(T v) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    for (size_t i = 0; i < sizeof(T); ++i) bytes += b[bigEndian ? sizeof(T) - 1 - i : i];
    return *this;
  }
  PlyBinary& vertices() {
    for (const auto& v : kPlyVertices) put(v[0]).put(v[1]).put(v[2]);
    return *this;
  }
  PlyBinary& face(const std::vector<int>& f) {
    put(uint8_t(f.size()));
    for (const int i : f) put(int32_t(i));
    return *this;
  }
  PlyBinary& faces() {
    for (const auto& f : kPlyFaces) face(f);
    return *this;
  }
};

inline std::string asciiPlyTetrahedron() { return plyHeader("ascii", 4, 4) + kPlyAsciiVertices + kPlyAsciiFaces; }

inline std::string binaryPlyTetrahedron(bool bigEndian) {
  return plyHeader(bigEndian ? "binary_big_endian" : "binary_little_endian", 4, 4) +
         PlyBinary(bigEndian).vertices().faces().bytes;
}

}  // namespace kasha::test
