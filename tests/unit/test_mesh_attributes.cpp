// Mesh attributes (core/shape.h MeshAttribute, read from PLY files by core/ply_validation.h) and
// the mesh_attribute texture (core/mesh_attribute_texture.h): the values of the file, named as
// Mitsuba 3 names them, interpolated over a triangle with its barycentrics (vertex attributes) or
// constant over it (face attributes, kept with their triangles when degenerate ones are removed),
// integers decoded from sRGB, ASCII and binary alike, and clear one-line errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <string>

#include "core/error.h"
#include "core/rgb_spectrum.h"
#include "scene/scene_loader.h"
#include "tests/temp_dir.h"

namespace kasha {
namespace {

// Vertex colours (color_0..2, floats; Mitsuba's "vertex_color"), a one-channel vertex value
// (rough_0: "vertex_rough") and face colours (red, green, blue as uchar: "face_color") of a unit
// square in two triangles, after a degenerate triangle (face 0, removed on loading).
const Vec3 kVertexColour[5] = {{0.1f, 0.2f, 0.3f}, {0.5f, 0.6f, 0.7f}, {0.9f, 0.1f, 0.4f}, {0.3f, 0.8f, 0.2f}, {1, 1, 1}};
const float kRough[5] = {0.1f, 0.2f, 0.4f, 0.8f, 0.5f};
const int kFaceBytes[3][3] = {{255, 0, 0}, {128, 64, 32}, {0, 255, 10}};
const char* kAsciiPly = R"(ply
format ascii 1.0
element vertex 5
property float x
property float y
property float z
property float color_0
property float color_1
property float color_2
property float rough_0
element face 3
property list uchar int vertex_indices
property uchar red
property uchar green
property uchar blue
end_header
0 0 0 0.1 0.2 0.3 0.1
1 0 0 0.5 0.6 0.7 0.2
1 1 0 0.9 0.1 0.4 0.4
0 1 0 0.3 0.8 0.2 0.8
2 0 0 1 1 1 0.5
3 0 1 4 255 0 0
3 0 1 2 128 64 32
3 0 2 3 0 255 10
)";

// IEC 61966-2-1's decoding of an 8-bit sRGB value.
float srgbByte(int b) {
  const double c = b / 255.0;
  return float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}

class MeshAttributes : public test::TempDirTest {
 protected:
  MeshAttributes() : TempDirTest("mesh_attributes") {}

  std::string write(const std::string& name, const std::string& bytes) const {
    std::ofstream(dir + "/" + name, std::ios::binary) << bytes;
    return dir + "/" + name;
  }
  // A scene with the mesh `file` under `material`.
  std::string scene(const std::string& file, const std::string& material) const {
    return write("scene.json", R"({
  "camera": {"position": [0.5, 0.5, 3], "look_at": [0.5, 0.5, 0], "fov": 40, "resolution": [8, 8]},
  "materials": {"m": )" + material + R"(},
  "shapes": [{"type": "mesh", "file": ")" + file + R"(", "material": "m"}],
  "lights": [{"type": "point", "position": [0, 0, 2], "intensity": 1}]
})");
  }
  std::string error(const std::string& file, const std::string& material) const {
    try {
      loadScene(scene(file, material));
    } catch (const InputError& e) {
      return e.what();
    }
    ADD_FAILURE() << "loaded";
    return "";
  }
};

// The reflectance a Lambertian's Bsdf has at (prim, bary) of shape 0.
float reflectanceAt(const Scene& s, uint32_t prim, Vec2 bary, float lambda) {
  Hit h;
  h.ng = Vec3(0, 0, 1);
  h.prim = prim;
  h.bary = bary;
  const Vec3 n(0, 0, 1);
  return s.bsdf(h, {&lambda, 1}).eval({TransportMode::Radiance, SpectralLobe::Elastic, lambda, lambda}, n, n) * kPi;
}

TEST_F(MeshAttributes, VertexValuesInterpolateFaceValuesAreConstant) {
  write("square.ply", kAsciiPly);
  const auto s = loadScene(scene("square.ply", R"({"type": "lambertian", "reflectance": 1,
      "reflectance_texture": {"type": "mesh_attribute", "name": "vertex_color"}})"));
  const Shape& shape = s->shapes[0];
  ASSERT_EQ(shape.indices.size(), 6u);  // the degenerate face is gone
  const MeshAttribute* colour = shape.attribute("vertex_color");
  ASSERT_NE(colour, nullptr);
  EXPECT_EQ(colour->channels, 3);
  // Triangle 0 is the file's face 1, corners 0, 1, 2: c = (1 − b1 − b2)·c0 + b1·c1 + b2·c2.
  for (const Vec2 b : {Vec2(0.2f, 0.3f), Vec2(0.0f, 0.0f), Vec2(0.7f, 0.1f)}) {
    const Vec3 expected = (1.0f - b.x - b.y) * kVertexColour[0] + b.x * kVertexColour[1] + b.y * kVertexColour[2];
    const Vec3 got = shape.attributeAt(*colour, 0, b);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], expected[k], 1e-6f);
    for (const float l : {450.0f, 600.0f})
      EXPECT_NEAR(reflectanceAt(*s, 0, b, l), rgbToSigmoid(expected)(l), 1e-6f) << b.x << " " << b.y << " " << l;
  }
  // Face colours: uchar values decoded from sRGB, one per triangle, after the removed one.
  const auto f = loadScene(scene("square.ply", R"({"type": "lambertian", "reflectance": 1,
      "reflectance_texture": {"type": "mesh_attribute", "name": "face_color"}})"));
  for (uint32_t prim = 0; prim < 2; ++prim) {
    const Vec3 expected(srgbByte(kFaceBytes[prim + 1][0]), srgbByte(kFaceBytes[prim + 1][1]), srgbByte(kFaceBytes[prim + 1][2]));
    for (const Vec2 b : {Vec2(0.1f, 0.1f), Vec2(0.6f, 0.3f)}) {
      const Vec3 got = f->shapes[0].attributeAt(*f->shapes[0].attribute("face_color"), prim, b);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], expected[k], 1e-6f);
      EXPECT_NEAR(reflectanceAt(*f, prim, b, 550.0f), rgbToSigmoid(expected)(550.0f), 1e-6f);
    }
  }
  // A one-channel attribute on a scalar: α = 1 × the interpolated value, as the material with that α.
  const auto r = loadScene(scene("square.ply", R"({"type": "rough_conductor", "reflectance": 1, "alpha": 1,
      "alpha_texture": {"type": "mesh_attribute", "name": "vertex_rough"}})"));
  const Vec2 b(0.25f, 0.5f);
  const float alpha = (1.0f - b.x - b.y) * kRough[0] + b.x * kRough[1] + b.y * kRough[2];
  Hit h;
  h.ng = Vec3(0, 0, 1);
  h.bary = b;
  const float lambda = 550.0f;
  const Bsdf textured = r->bsdf(h, {&lambda, 1});
  const auto plain = loadScene(scene("square.ply", R"({"type": "rough_conductor", "reflectance": 1, "alpha": )" +
                                                       std::to_string(alpha) + "}"));
  const Bsdf untextured = plain->bsdf(h, {&lambda, 1});
  const Vec3 wi = glm::normalize(Vec3(0.3f, 0.1f, 0.8f)), wo = glm::normalize(Vec3(-0.2f, 0.2f, 0.9f));
  EXPECT_NEAR(textured.eval({TransportMode::Radiance, SpectralLobe::Elastic, lambda, lambda}, wi, wo),
              untextured.eval({TransportMode::Radiance, SpectralLobe::Elastic, lambda, lambda}, wi, wo), 1e-4f);
}

// The same vertex colours from a binary file (r, g, b floats, big-endian) read the same.
TEST_F(MeshAttributes, BinaryFilesReadTheSameValues) {
  std::string ply = "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                    "property float z\nproperty float r\nproperty float g\nproperty float b\nelement face 1\n"
                    "property list uchar int vertex_indices\nend_header\n";
  const auto put = [&](const void* p, size_t n) {
    const char* c = static_cast<const char*>(p);
    for (size_t k = n; k-- > 0;) ply += c[k];  // big-endian on this little-endian machine
  };
  const float corners[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  for (int v = 0; v < 3; ++v) {
    for (float x : corners[v]) put(&x, 4);
    for (int k = 0; k < 3; ++k) put(&kVertexColour[v][k], 4);
  }
  ply += char(3);
  for (int32_t i : {0, 1, 2}) put(&i, 4);
  write("tri.ply", ply);
  const auto s = loadScene(scene("tri.ply", R"({"type": "lambertian", "reflectance": 1,
      "reflectance_texture": {"type": "mesh_attribute", "name": "vertex_color"}})"));
  const MeshAttribute* a = s->shapes[0].attribute("vertex_color");
  ASSERT_NE(a, nullptr);
  for (int v = 0; v < 3; ++v) EXPECT_EQ(a->values[size_t(v)], kVertexColour[v]);
}

TEST_F(MeshAttributes, ClearErrors) {
  write("square.ply", kAsciiPly);
  const auto texture = [](const std::string& name, const std::string& field = "reflectance_texture") {
    return R"({"type": "lambertian", "reflectance": 1, ")" + field + R"(": {"type": "mesh_attribute", "name": ")" + name + "\"}}";
  };
  const std::string at = dir + "/scene.json: /shapes/0/";
  EXPECT_EQ(error("square.ply", texture("vertex_weight")),
            at + "file: " + dir + "/square.ply: element vertex: has no properties for the mesh attribute 'vertex_weight' "
                 "(weight_x, weight_y, weight_z or one of the other namings)");
  EXPECT_EQ(error("square.ply", R"({"type": "rough_conductor", "reflectance": 1, "alpha": 1,
      "alpha_texture": {"type": "mesh_attribute", "name": "vertex_color"}})"),
            at + "material: material 'm' reads the mesh attribute 'vertex_color' as a scalar, but it has 3 channels in this mesh");
  EXPECT_EQ(error("square.ply", texture("colour")),
            dir + "/scene.json: /materials/m/reflectance_texture/name: 'colour' is not a mesh attribute's name (vertex_... or face_...)");
  std::string outside = kAsciiPly;
  outside.replace(outside.find("0.5 0.6 0.7"), 3, "1.5");
  write("outside.ply", outside);
  EXPECT_NE(error("outside.ply", texture("vertex_color")).find("outside.ply:18: vertex 1: property color_0 is 1.500000, outside [0, 1] (mesh attribute vertex_color)"),
            std::string::npos);
  std::string quad = kAsciiPly;
  quad.replace(quad.find("3 0 2 3 0 255 10"), 16, "4 0 1 2 3 0 255 10");
  write("quad.ply", quad);
  EXPECT_NE(error("quad.ply", texture("face_color")).find("face 2: has 4 vertex indices; a mesh with face attributes needs triangles"),
            std::string::npos);
  write("square.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_EQ(error("square.obj", texture("vertex_color")),
            at + "material: material 'm' reads the mesh attribute 'vertex_color', which only PLY meshes carry");
}

}  // namespace
}  // namespace kasha
