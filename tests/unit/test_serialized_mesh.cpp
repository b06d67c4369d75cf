// Mitsuba serialized meshes (core/serialized_mesh.h): files written here by an independent writer
// (zlib's compress2, the layout of Mitsuba 3's documentation) read back exactly, versions 3, 4 and
// 5 (packed records, maps, attributes, encoded frames, the face-normal flag), single and double
// precision, the mesh shape_index names; truncated files, forged headers and
// dictionaries, counts beyond the data or the memory limit, indices beyond the vertices and more
// data than declared are one-line errors naming the file and the field; the scene loader and the
// Mitsuba importer place the mesh (normals by the inverse transpose, face_normals).
#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include "core/error.h"
#include "core/memory_budget.h"
#include "core/serialized_mesh.h"
#include "scene/scene_loader.h"
#include "tests/expect_contains.h"
#include "tests/temp_dir.h"

namespace kasha {
namespace {

constexpr uint64_t kLimit = uint64_t(1) << 30;

template <typename T>
void put(std::string& out, T value) {  // little-endian, as the format is (and this machine)
  out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

struct TestMesh {
  std::vector<float> positions, normals, uvs, colors;  // 3, 3, 2, 3 per vertex; empty: absent
  std::vector<uint32_t> indices;
  bool doubles = false;
  std::string name = "m";
  uint64_t vertices() const { return positions.size() / 3; }
};

// The uncompressed content of one mesh (Mitsuba 3 docs, "Format description", versions 3 and 4),
// with counts that may be forged.
std::string content(const TestMesh& m, int version, uint64_t vertices, uint64_t faces) {
  std::string out;
  const uint32_t flags = (m.normals.empty() ? 0 : 0x1) | (m.uvs.empty() ? 0 : 0x2) | (m.colors.empty() ? 0 : 0x8) |
                         (m.doubles ? 0x2000 : 0x1000);
  put(out, flags);
  if (version == 4) out += m.name + '\0';
  put(out, vertices);
  put(out, faces);
  for (const auto* array : {&m.positions, &m.normals, &m.uvs, &m.colors})
    for (const float v : *array) m.doubles ? put(out, double(v)) : put(out, v);
  for (const uint32_t i : m.indices) put(out, i);
  return out;
}

// Version 5's content: packed records, optional maps, custom attributes ("vertex_color" with 3
// channels, "face_id" with 1); `frames` replaces the normals by encoded frames (flag 0x0002).
struct V5Options {
  bool identityMaps = false, attributes = false, frames = false, faceNormals = false;
  uint32_t flagsOverride = 0;
  uint64_t surfacePoints = 0;  // forged P when set
};
std::string contentV5(const TestMesh& m, const V5Options& o = {}) {
  std::string out;
  uint32_t flags = 0x1000 | (m.normals.empty() ? 0 : 0x1) | (o.frames ? 0x2 : 0) | (m.uvs.empty() ? 0 : 0x4) | (o.faceNormals ? 0x10 : 0);
  if (o.flagsOverride) flags = o.flagsOverride;
  put(out, flags);
  put(out, uint32_t(m.name.size()));
  out += m.name;
  const uint64_t v = m.vertices(), f = m.indices.size() / 3;
  put(out, v);
  put(out, f);
  put(out, o.surfacePoints ? o.surfacePoints : o.identityMaps ? v : 0);
  put(out, uint64_t(o.identityMaps ? v : 0));
  for (uint64_t i = 0; i < v; ++i) {
    for (int k = 0; k < 3; ++k) put(out, m.positions[3 * i + k]);
    for (int k = 0; k < 3; ++k) put(out, m.normals.empty() ? 0.0f : m.normals[3 * i + k]);
    for (int k = 0; k < 2; ++k) put(out, m.uvs.empty() ? 0.0f : m.uvs[2 * i + k]);
  }
  for (uint64_t t = 0; t < f; ++t) {
    for (int k = 0; k < 3; ++k) put(out, m.indices[3 * t + k]);
    put(out, uint32_t(0));  // BSDF index
  }
  if (o.identityMaps || o.surfacePoints)
    for (int map = 0; map < 2; ++map)
      for (uint64_t i = 0; i < v; ++i) put(out, uint32_t(i));
  put(out, uint32_t(o.attributes ? 2 : 0));
  if (o.attributes) {
    for (const auto& [name, channels, rows] : {std::tuple<std::string, uint32_t, uint64_t>{"vertex_color", 3, v},
                                               std::tuple<std::string, uint32_t, uint64_t>{"face_id", 1, f}}) {
      put(out, uint32_t(name.size()));
      out += name;
      put(out, uint8_t(0));
      put(out, channels);
      for (uint64_t i = 0; i < rows * channels; ++i) put(out, 0.25f);
    }
  }
  return out;
}

std::string compress(const std::string& raw) {
  uLongf size = compressBound(uLong(raw.size()));
  std::string out(size, '\0');
  EXPECT_EQ(compress2(reinterpret_cast<Bytef*>(out.data()), &size, reinterpret_cast<const Bytef*>(raw.data()),
                      uLong(raw.size()), Z_DEFAULT_COMPRESSION),
            Z_OK);
  out.resize(size);
  return out;
}

// A file of meshes given by their uncompressed contents, with the dictionary at the end.
std::string file(const std::vector<std::string>& contents, int version) {
  std::string out;
  std::vector<uint64_t> offsets;
  for (const std::string& c : contents) {
    offsets.push_back(out.size());
    put(out, uint16_t(0x041C));
    put(out, uint16_t(version));
    out += compress(c);
  }
  for (const uint64_t o : offsets) version == 3 ? put(out, uint32_t(o)) : put(out, o);
  put(out, uint32_t(contents.size()));
  return out;
}

std::string file(const std::vector<TestMesh>& meshes, int version) {
  std::vector<std::string> contents;
  for (const TestMesh& m : meshes) contents.push_back(content(m, version, m.vertices(), m.indices.size() / 3));
  return file(contents, version);
}

// A unit square in z = 0 (two triangles) with normals, uvs and colours; and a triangle.
TestMesh square() {
  TestMesh m;
  m.positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  m.normals = {0, 0, 1, 0, 0.6f, 0.8f, 0, 0, 1, 0.6f, 0, 0.8f};
  m.uvs = {0, 0, 1, 0, 1, 0.25f, 0, 0.75f};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}
TestMesh triangle() {
  TestMesh m;
  m.positions = {0, 0, 0, 2, 0, 0, 0, 3, 0.5f};
  m.indices = {0, 2, 1};
  return m;
}

Shape read(const std::string& bytes, uint64_t index, uint64_t limit = kLimit) {
  Shape s;
  readSerializedMesh(bytes, "m.serialized", index, limit, s);
  return s;
}

// The one-line message readSerializedMesh throws for `bytes`, or "" (and a failure) if it reads them.
std::string problem(const std::string& bytes, uint64_t index = 0, uint64_t limit = kLimit) {
  try {
    read(bytes, index, limit);
  } catch (const std::runtime_error& e) {  // InputError, MemoryLimitError
    const std::string m = e.what();
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    EXPECT_NE(m.find("m.serialized"), std::string::npos) << m;
    return m;
  }
  ADD_FAILURE() << "read, expected an error";
  return "";
}

void expectSquare(const Shape& s) {
  const TestMesh m = square();
  ASSERT_EQ(s.positions.size(), 4u);
  for (size_t v = 0; v < 4; ++v) EXPECT_EQ(s.positions[v], Vec3(m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]));
  EXPECT_EQ(s.indices, m.indices);
  ASSERT_EQ(s.cornerNormals.size(), 6u);
  ASSERT_EQ(s.cornerUvs.size(), 6u);
  for (size_t c = 0; c < 6; ++c) {
    const uint32_t v = m.indices[c];
    EXPECT_EQ(s.cornerNormals[c], Vec3(m.normals[3 * v], m.normals[3 * v + 1], m.normals[3 * v + 2])) << c;
    // Mitsuba's v counts from the image's top, kasha's from its bottom.
    EXPECT_EQ(s.cornerUvs[c], Vec2(m.uvs[2 * v], 1.0f - m.uvs[2 * v + 1])) << c;
  }
}

TEST(SerializedMesh, ReadsEveryMeshOfVersions3And4Exactly) {
  for (const int version : {3, 4})
    for (const bool doubles : {false, true}) {
      SCOPED_TRACE(::testing::Message() << "version " << version << (doubles ? " double" : " single"));
      TestMesh a = triangle(), b = square();
      a.doubles = b.doubles = doubles;
      b.colors = {1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};  // read past, not kept
      const std::string bytes = file({a, b}, version);
      const Shape first = read(bytes, 0);
      ASSERT_EQ(first.positions.size(), 3u);
      EXPECT_EQ(first.positions[2], Vec3(0, 3, 0.5f));
      EXPECT_EQ(first.indices, (std::vector<uint32_t>{0, 2, 1}));
      EXPECT_TRUE(first.cornerNormals.empty());
      EXPECT_TRUE(first.cornerUvs.empty());
      expectSquare(read(bytes, 1));  // shape_index selects the second mesh
    }
}

TEST(SerializedMesh, ForgedHeadersAndDictionariesAreRefused) {
  const std::string good = file({triangle(), square()}, 4);
  EXPECT_CONTAINS(problem("PK\3\4 not a mesh"), "m.serialized: header: not a Mitsuba serialized mesh");
  EXPECT_CONTAINS(problem(std::string("\x1c\x04\x09\x00", 4)), "m.serialized: header: unknown version");
  std::string v7 = good;
  v7[2] = 7;
  EXPECT_CONTAINS(problem(v7), "unknown version 7");
  EXPECT_CONTAINS(problem(good, 2), "m.serialized: shape_index: 2 is out of range: the file holds 2 meshes");
  std::string manyMeshes = good;
  std::memset(&manyMeshes[manyMeshes.size() - 4], 0xff, 4);
  EXPECT_CONTAINS(problem(manyMeshes, 1), "m.serialized: dictionary: declares 4294967295 meshes");
  std::string farOffset = good;  // mesh 1's offset past the end
  std::memset(&farOffset[farOffset.size() - 12], 0x7f, 8);
  EXPECT_CONTAINS(problem(farOffset, 1), "m.serialized: dictionary: mesh 1 starts at byte");
  std::string wrongOffset = good;  // mesh 1's offset inside mesh 0's data
  wrongOffset[wrongOffset.size() - 12] = 9, wrongOffset[wrongOffset.size() - 11] = 0;
  EXPECT_CONTAINS(problem(wrongOffset, 1), "m.serialized: mesh 1: no header");
}

TEST(SerializedMesh, TruncatedAndCorruptDataAreRefused) {
  const std::string one = file({square()}, 3);
  const size_t dictionary = 4 + 4;  // v3: one uint32 offset and the count
  // Cut anywhere inside the compressed stream: an error, never a partial mesh.
  for (size_t cut = 4; cut + dictionary < one.size(); cut += 7) {
    const std::string m = problem(one.substr(0, cut));
    EXPECT_TRUE(m.find("truncated") != std::string::npos || m.find("ends before") != std::string::npos ||
                m.find("corrupt") != std::string::npos) << cut << ": " << m;
  }
  std::string flipped = one;
  flipped[6] ^= 0x55;
  problem(flipped);
  // Compressed data holding more than the counts declare.
  const TestMesh m = square();
  EXPECT_CONTAINS(problem(file({content(m, 3, 4, 1)}, 3)), "m.serialized: mesh 0: the compressed data holds more");
  EXPECT_CONTAINS(problem(file({content(m, 3, 4, 3)}, 3)), "m.serialized: mesh 0: data: the mesh's data ends before it");
}

TEST(SerializedMesh, CountsAreCheckedBeforeAllocating) {
  const TestMesh m = square();
  EXPECT_CONTAINS(problem(file({content(m, 4, 0, 2)}, 4)), "mesh 0: holds no triangles");
  EXPECT_CONTAINS(problem(file({content(m, 4, uint64_t(1) << 40, 2)}, 4)), "mesh 0: vertex count: 1099511627776 is more than 32-bit indices reach");
  EXPECT_CONTAINS(problem(file({content(m, 4, 4, uint64_t(1) << 62)}, 4)), "mesh 0: face count");
  // Counts a few hundred compressed bytes cannot hold: refused before any allocation.
  EXPECT_CONTAINS(problem(file({content(m, 4, 4000000000u, 1000000000u)}, 4)), "mesh 0: counts: 4000000000 vertices and 1000000000 triangles need");
  // Counts the data holds, but not the memory limit.
  TestMesh big;
  for (int i = 0; i < 3 * 30000; ++i) {
    big.positions.push_back(float(i) * 0.37f);
    big.indices.push_back(uint32_t(i * 7919) % 30000u);
  }
  const std::string bytes = file({big}, 4);
  EXPECT_CONTAINS(problem(bytes, 0, 1 << 20), "more than the memory limit");
  EXPECT_EQ(read(bytes, 0).indices.size(), 90000u);
}

TEST(SerializedMesh, IndicesAndNumbersAreChecked) {
  TestMesh m = square();
  m.indices[4] = 4;
  EXPECT_CONTAINS(problem(file({m}, 4)), "m.serialized: mesh 0: face 1: vertex index 4 is not below the vertex count 4");
  m = square();
  m.positions[4] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_CONTAINS(problem(file({m}, 4)), "m.serialized: mesh 0: vertex 1: position is not finite");
  m = square();
  m.doubles = true;
  m.uvs[7] = std::numeric_limits<float>::infinity();
  EXPECT_CONTAINS(problem(file({m}, 3)), "vertex 3: texture coordinate is not finite");
}

TEST(SerializedMesh, ReadsVersion5PackedRecords) {
  V5Options full;
  full.identityMaps = full.attributes = true;
  const std::string bytes = file({contentV5(triangle()), contentV5(square(), full)}, 5);
  Shape first;
  EXPECT_FALSE(readSerializedMesh(bytes, "m.serialized", 0, kLimit, first));
  EXPECT_EQ(first.positions.size(), 3u);
  EXPECT_TRUE(first.cornerNormals.empty() && first.cornerUvs.empty());
  expectSquare(read(bytes, 1));

  // The face-normal flag is reported to the caller.
  V5Options flat;
  flat.faceNormals = true;
  Shape s;
  EXPECT_TRUE(readSerializedMesh(file({contentV5(square(), flat)}, 5), "m.serialized", 0, kLimit, s));
  EXPECT_EQ(s.cornerNormals.size(), 6u);  // kept: the caller decides

  // Encoded frames: a rotation by θ about x is the quaternion (cos θ/2, sin θ/2, 0, 0), modified
  // Rodrigues parameters (tan θ/4, 0, 0); it turns the normal e_z to (0, −sin θ, cos θ).
  TestMesh framed = triangle();
  const float theta = 0.6f;
  framed.normals = {0, 0, 0, std::tan(theta / 4), 0, 0, 0, 0, 0};
  V5Options frames;
  frames.frames = true;
  const Shape f = read(file({contentV5(framed, frames)}, 5), 0);
  ASSERT_EQ(f.cornerNormals.size(), 3u);
  EXPECT_NEAR(glm::length(f.cornerNormals[0] - Vec3(0, 0, 1)), 0.0f, 1e-6f);
  // Corner 2 of the triangle (0, 2, 1) is vertex 1.
  EXPECT_NEAR(glm::length(f.cornerNormals[2] - Vec3(0, -std::sin(theta), std::cos(theta))), 0.0f, 1e-6f);
}

TEST(SerializedMesh, Version5HeadersMapsAndAttributesAreChecked) {
  V5Options o;
  o.flagsOverride = 0x0001;  // no single-precision flag
  EXPECT_CONTAINS(problem(file({contentV5(square(), o)}, 5)), "m.serialized: mesh 0: flags: version 5 data must be single precision");
  o.flagsOverride = 0x1002;
  EXPECT_CONTAINS(problem(file({contentV5(square(), o)}, 5)), "mesh 0: flags: tangents without normals");
  V5Options forged;
  forged.surfacePoints = 9;
  EXPECT_CONTAINS(problem(file({contentV5(square(), forged)}, 5)), "mesh 0: counts: more surface points or normal groups than vertices");
  forged.surfacePoints = 3;  // the identity map then reaches index 3
  EXPECT_CONTAINS(problem(file({contentV5(square(), forged)}, 5)), "mesh 0: vertex 3: map index beyond its 3 entries");
  // An attribute of 5 channels.
  V5Options attributes;
  attributes.attributes = true;
  std::string raw = contentV5(square(), attributes);
  const size_t channels = raw.find("vertex_color") + 12 + 1;
  raw[channels] = 5;
  EXPECT_CONTAINS(problem(file({raw}, 5)), "mesh 0: attribute 0: 5 channels (1 to 4)");
  // A name longer than any.
  std::string named = contentV5(square());
  std::memset(&named[4], 0xff, 4);
  EXPECT_CONTAINS(problem(file({named}, 5)), "mesh 0: name: a name longer than 65536 bytes");
}

class SerializedScene : public test::TempDirTest {
 protected:
  SerializedScene() : TempDirTest("serialized") {}
  std::string write(const std::string& name, const std::string& bytes) const {
    const std::string path = dir + "/" + name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }
};

TEST_F(SerializedScene, MitsubaShapePlacesTheMeshAndItsNormals) {
  write("m.serialized", file({triangle(), square()}, 4));
  const std::string sensor =
      R"(<sensor type="perspective"><float name="fov" value="45"/><transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
         <film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="4"/></film></sensor>
         <emitter type="point"><point name="position" x="0" y="0" z="3"/><spectrum name="intensity" value="1"/></emitter>)";
  // Stretched by 2 along x: positions double in x, normals (0, 0.6, 0.8) and (0.6, 0, 0.8) follow
  // the inverse transpose, (0.3, 0, 0.8) before normalisation.
  const std::string scene = write("s.xml", R"(<scene version="3.0.0">)" + sensor + R"(
    <shape type="serialized"><string name="filename" value="m.serialized"/><integer name="shape_index" value="1"/>
      <transform name="to_world"><scale x="2" y="1" z="1"/><translate z="1"/></transform></shape>
    <shape type="serialized"><string name="filename" value="m.serialized"/><integer name="shape_index" value="1"/>
      <boolean name="face_normals" value="true"/></shape>
    <shape type="serialized"><string name="filename" value="m.serialized"/></shape></scene>)");
  const auto s = loadScene(scene);
  ASSERT_EQ(s->shapes.size(), 3u);
  const Shape& placed = s->shapes[0];
  EXPECT_EQ(placed.positions[2], Vec3(2, 1, 1));
  EXPECT_NEAR(placed.area, 2.0f, 1e-6f);
  const Vec3 n = placed.shadingNormal(1, Vec2(0.0f, 1.0f), Vec3(0, 0, 1));  // corner 2 of triangle 1: vertex 3
  EXPECT_NEAR(n.x, 0.3f / std::sqrt(0.73f), 1e-6f);
  EXPECT_NEAR(n.z, 0.8f / std::sqrt(0.73f), 1e-6f);
  EXPECT_TRUE(s->shapes[1].cornerNormals.empty());
  EXPECT_EQ(s->shapes[2].indices.size(), 3u);  // shape_index 0 by default

  // Version 5's face-normal flag applies where the shape leaves face_normals unset.
  V5Options flat;
  flat.faceNormals = true;
  write("flat.serialized", file({contentV5(square(), flat)}, 5));
  const auto v5 = loadScene(write("v5.xml", R"(<scene version="3.0.0">)" + sensor + R"(
    <shape type="serialized"><string name="filename" value="flat.serialized"/></shape>
    <shape type="serialized"><string name="filename" value="flat.serialized"/><boolean name="face_normals" value="false"/></shape></scene>)"));
  EXPECT_TRUE(v5->shapes[0].cornerNormals.empty());
  EXPECT_EQ(v5->shapes[1].cornerNormals.size(), 6u);

  const std::string wrong = write("w.xml", R"(<scene version="3.0.0">)" + sensor + R"(
    <shape type="serialized"><string name="filename" value="m.serialized"/><integer name="shape_index" value="5"/></shape></scene>)");
  try {
    loadScene(wrong);
    ADD_FAILURE() << "loaded a missing mesh";
  } catch (const InputError& e) {
    EXPECT_CONTAINS(e.what(), "m.serialized: shape_index: 5 is out of range");
  }
}

}  // namespace
}  // namespace kasha
