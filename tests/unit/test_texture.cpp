// Textures (core/texture.h), texture coordinates of shapes (core/shape.h) and the textured Jung
// material (materials/jung_bbrrdf.h): lookup, files, errors, and that a textured material with a
// constant image renders exactly as the untextured one.
#include <gtest/gtest.h>
#include <unistd.h>

#include <ImfRgbaFile.h>
#include <png.h>
#include <zlib.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/memory_budget.h"
#include "scene/scene_loader.h"
#include "core/texture.h"
#include "integrators/integrator_factory.h"
#include "integrators/render_loop.h"
#include "materials/jung_bbrrdf.h"
#include "materials/material_json.h"
#include "tests/texture_files.h"

namespace kasha {
namespace {

namespace fs = std::filesystem;
using test::renderFilm;
using test::TextureFiles;

// ---------------------------------------------------------------------------------------------
// Lookup

// The centre of texel (x, y) of a w×h image.
Vec2 centre(int x, int y, int w, int h) { return Vec2((x + 0.5f) / float(w), 1.0f - (y + 0.5f) / float(h)); }

TEST(TextureLookup, NearestTexelOrientationAndRepeat) {
  // 3×2: row 0 (top) = 0.1 0.2 0.3, row 1 (bottom) = 0.4 0.5 0.6
  const ImageTexture t(3, 2, 1, {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f}, TextureWrap::Repeat, TextureFilter::Nearest);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) {
      const Vec2 c = centre(x, y, 3, 2);
      const float expect = 0.1f * float(1 + x + 3 * y);
      EXPECT_FLOAT_EQ(t.scalar(c), expect) << x << ", " << y;
      // Anywhere inside the texel, and repeated by whole periods in both directions.
      EXPECT_FLOAT_EQ(t.scalar(c + Vec2(0.16f, -0.24f)), expect);
      EXPECT_FLOAT_EQ(t.scalar(c + Vec2(2.0f, -3.0f)), expect);
      EXPECT_FLOAT_EQ(t.scalar(c + Vec2(-1.0f, 5.0f)), expect);
    }
  EXPECT_FLOAT_EQ(t.scalar(Vec2(0.0f, 0.0f)), 0.4f) << "(0, 0) is the bottom-left corner";
  EXPECT_FLOAT_EQ(t.scalar(Vec2(0.999f, 0.999f)), 0.3f) << "(1, 1) is the top-right corner";
  EXPECT_FLOAT_EQ(t.scalar(Vec2(std::nanf(""), 0.7f)), t.scalar(Vec2(0.0f))) << "non-finite uv: no crash";
}

// Bilinear filtering reproduces texel values at texel centres and a function linear in (x, y)
// exactly everywhere between the centres (the closed form of bilinear interpolation).
TEST(TextureLookup, BilinearIsExactOnLinearFunctions) {
  const int w = 5, h = 4;
  const auto f = [](float x, float y) { return 0.1f + 0.1f * x + 0.05f * y; };  // x, y in texel units
  std::vector<float> texels;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) texels.push_back(f(float(x), float(y)));
  const ImageTexture t(w, h, 1, texels, TextureWrap::Clamp, TextureFilter::Bilinear);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) EXPECT_FLOAT_EQ(t.scalar(centre(x, y, w, h)), f(float(x), float(y)));
  for (const Vec2 p : {Vec2(1.3f, 2.7f), Vec2(0.5f, 0.5f), Vec2(3.99f, 0.01f), Vec2(2.25f, 1.75f)}) {
    const Vec2 uv((p.x + 0.5f) / w, 1.0f - (p.y + 0.5f) / h);
    EXPECT_NEAR(t.scalar(uv), f(p.x, p.y), 1e-6f) << p.x << ", " << p.y;
  }
  // Half-way between two texels, the mean; at a corner of four, the mean of four.
  const ImageTexture q(2, 2, 1, {0.0f, 0.2f, 0.4f, 1.0f}, TextureWrap::Clamp, TextureFilter::Bilinear);
  EXPECT_FLOAT_EQ(q.scalar(Vec2(0.5f, 0.75f)), 0.1f);
  EXPECT_FLOAT_EQ(q.scalar(Vec2(0.5f, 0.5f)), 0.4f);
}

// Wrap modes on a 4×1 strip 0.1 0.2 0.3 0.4: texel index −1, 4 and 5, and the seam at u = 0.
TEST(TextureLookup, WrapModes) {
  const std::vector<float> strip = {0.1f, 0.2f, 0.3f, 0.4f};
  const auto at = [&](TextureWrap w, TextureFilter f, float u) { return ImageTexture(4, 1, 1, strip, w, f).scalar(Vec2(u, 0.5f)); };
  const float left = -0.125f, right = 1.125f, right2 = 1.375f;  // centres of texels −1, 4, 5
  for (const TextureFilter f : {TextureFilter::Nearest, TextureFilter::Bilinear}) {
    EXPECT_FLOAT_EQ(at(TextureWrap::Repeat, f, left), 0.4f);
    EXPECT_FLOAT_EQ(at(TextureWrap::Repeat, f, right), 0.1f);
    EXPECT_FLOAT_EQ(at(TextureWrap::Repeat, f, right2), 0.2f);
    EXPECT_FLOAT_EQ(at(TextureWrap::Clamp, f, left), 0.1f);
    EXPECT_FLOAT_EQ(at(TextureWrap::Clamp, f, right), 0.4f);
    EXPECT_FLOAT_EQ(at(TextureWrap::Clamp, f, right2), 0.4f);
    EXPECT_FLOAT_EQ(at(TextureWrap::Mirror, f, left), 0.1f);
    EXPECT_FLOAT_EQ(at(TextureWrap::Mirror, f, right), 0.4f);
    EXPECT_FLOAT_EQ(at(TextureWrap::Mirror, f, right2), 0.3f);
    EXPECT_FLOAT_EQ(at(TextureWrap::Mirror, f, -1.375f), 0.3f) << "period 8 texels: texel −6 is texel 2";
    EXPECT_FLOAT_EQ(at(TextureWrap::Repeat, f, 1024.375f), 0.2f) << "large uv";
    EXPECT_FLOAT_EQ(at(TextureWrap::Mirror, f, -1023.375f), 0.3f) << "large uv";
  }
  // At u = 0 bilinear filtering blends texel 0 with texel −1, which the wrap mode decides.
  EXPECT_FLOAT_EQ(at(TextureWrap::Repeat, TextureFilter::Bilinear, 0.0f), 0.25f);
  EXPECT_FLOAT_EQ(at(TextureWrap::Clamp, TextureFilter::Bilinear, 0.0f), 0.1f);
  EXPECT_FLOAT_EQ(at(TextureWrap::Mirror, TextureFilter::Bilinear, 0.0f), 0.1f);
}

TEST(TextureLookup, RgbTexelsFilterPerChannel) {
  const ImageTexture t(2, 1, 3, {1.0f, 0.0f, 0.2f, 0.0f, 1.0f, 0.4f}, TextureWrap::Clamp, TextureFilter::Bilinear);
  const Vec3 mid = t.rgb(Vec2(0.5f, 0.5f));
  EXPECT_FLOAT_EQ(mid.x, 0.5f);
  EXPECT_FLOAT_EQ(mid.y, 0.5f);
  EXPECT_FLOAT_EQ(mid.z, 0.3f);
  EXPECT_EQ(t.rgb(Vec2(0.25f, 0.5f)), Vec3(1.0f, 0.0f, 0.2f));
}

// ---------------------------------------------------------------------------------------------
// Files

TEST_F(TextureFiles, PngChannelsAreDataValues) {
  // 2×1: (255, 0, 51, 255) (0, 102, 204, 0)
  const std::string p = writePng("a.png", 2, 1, {255, 0, 51, 255, 0, 102, 204, 0});
  TextureLoader loader(kDefaultMemoryLimit);
  const auto at = [&](TextureChannel c, int x) {
    return loader.load(p, c, TextureWrap::Repeat, TextureFilter::Nearest)->scalar(Vec2((x + 0.5f) / 2, 0.5f));
  };
  EXPECT_FLOAT_EQ(at(TextureChannel::R, 0), 1.0f);
  EXPECT_FLOAT_EQ(at(TextureChannel::G, 1), 0.4f);
  EXPECT_FLOAT_EQ(at(TextureChannel::B, 0), 0.2f);
  EXPECT_FLOAT_EQ(at(TextureChannel::A, 1), 0.0f);
  EXPECT_FLOAT_EQ(at(TextureChannel::Mean, 1), (0.0f + 0.4f + 0.8f) / 3.0f);
  EXPECT_FLOAT_EQ(at(TextureChannel::Luminance, 1), 0.7152f * 0.4f + 0.0722f * 0.8f);  // Rec. 709 Y
  const auto rgb = loader.load(p, TextureChannel::Rgb, TextureWrap::Repeat, TextureFilter::Nearest);
  EXPECT_EQ(rgb->channels(), 3);
  EXPECT_EQ(rgb->rgb(Vec2(0.75f, 0.5f)), Vec3(0.0f, 0.4f, 0.8f));
  EXPECT_EQ(loader.load(p, TextureChannel::R, TextureWrap::Repeat, TextureFilter::Nearest).get(),
            loader.load(p, TextureChannel::R, TextureWrap::Repeat, TextureFilter::Nearest).get())
      << "the same texture is loaded once";
  EXPECT_EQ(loader.bytes(), (6 * 2 + 3 * 2) * sizeof(float)) << "six one-channel textures and one RGB of 2 pixels";
}

TEST_F(TextureFiles, ExrValuesAndRange) {
  const std::string p = writeExr("a.exr", 2, 2, {0.0f, 0.25f, 0.5f, 1.0f});
  TextureLoader loader(kDefaultMemoryLimit);
  const auto t = loader.load(p, TextureChannel::Mean, TextureWrap::Repeat, TextureFilter::Nearest);
  EXPECT_FLOAT_EQ(t->scalar(Vec2(0.75f, 0.75f)), 0.25f);
  EXPECT_FLOAT_EQ(t->scalar(Vec2(0.25f, 0.25f)), 0.5f);
  const std::string bad = writeExr("bad.exr", 2, 1, {0.5f, 1.5f});
  try {
    loader.load(bad, TextureChannel::Mean, TextureWrap::Repeat, TextureFilter::Bilinear);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "value 1.500000 at pixel (1, 0) is outside [0, 1]");
  }
}

// The memory limit is checked from the header, before decoding: a PNG whose header claims
// 16000×16000 pixels (3 GB of RGB floats) but holds the data of one pixel is refused for its
// size, not for its data. Several textures count together.
TEST_F(TextureFiles, MemoryLimitFromTheHeader) {
  const std::string p = writePng("big.png", 1, 1, {255, 255, 255, 255});
  std::string bytes;
  {
    std::ifstream in(p, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  ASSERT_EQ(bytes.substr(12, 4), "IHDR");
  for (int k = 0; k < 2; ++k) {  // width and height, big-endian
    const uint32_t v = 16000;
    for (int b = 0; b < 4; ++b) bytes[size_t(16 + 4 * k + b)] = char((v >> (24 - 8 * b)) & 0xff);
  }
  const uLong crc = crc32(0, reinterpret_cast<const Bytef*>(bytes.data() + 12), 17);  // type + data
  for (int b = 0; b < 4; ++b) bytes[size_t(29 + b)] = char((crc >> (24 - 8 * b)) & 0xff);
  std::ofstream(p, std::ios::binary) << bytes;
  try {
    TextureLoader(uint64_t(1) << 30).load(p, TextureChannel::Rgb, TextureWrap::Repeat, TextureFilter::Bilinear);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), p + ": decoding this texture (16000×16000 pixels) besides the scene's textures before it "
                                     "(0 bytes) needs 4.77 GiB, more than the memory limit of 1.00 GiB (raise it with "
                                     "--memory-limit)");
  }
  // Two 64×64 textures of 16 KiB (+ 32 KiB while decoding) each fit 56 KiB one by one, not together.
  const std::string a = writePng("a.png", 64, 64, std::vector<unsigned char>(64 * 64 * 4, 128));
  TextureLoader loader(56 << 10);
  EXPECT_NO_THROW(loader.load(a, TextureChannel::R, TextureWrap::Repeat, TextureFilter::Bilinear));
  EXPECT_THROW(loader.load(a, TextureChannel::G, TextureWrap::Repeat, TextureFilter::Bilinear), InputError);
}

// Errors in a scene's material name the scene file, the field and the image file.
TEST_F(TextureFiles, ClearErrors) {
  const SpectrumContext ctx{"scene.json", dir, nullptr};
  const auto error = [&](const nlohmann::json& extra) -> std::string {
    nlohmann::json v = {{"type", "jung_fluorescent"}, {"absorption", 0.5}, {"emission", 1.0},
                        {"reflectance", 0.5}, {"c", 0.5}, {"Q", 0.5}};
    v.update(extra);
    try {
      parseMaterial(v, ctx, "/materials/ink", WavelengthRange{});
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  const std::string at = "scene.json: /materials/ink/";
  EXPECT_EQ(error({{"c_texture", "missing.png"}}),
            at + "c_texture: " + dir + "/missing.png: cannot open texture (No such file or directory)");
  writeText("garbage.png", "not an image");
  EXPECT_EQ(error({{"c_texture", "garbage.png"}}).rfind(at + "c_texture: " + dir + "/garbage.png: cannot read PNG", 0), 0u);
  writeText("garbage.exr", "not an image");
  EXPECT_EQ(error({{"Q_texture", "garbage.exr"}}).rfind(at + "Q_texture: " + dir + "/garbage.exr: cannot read OpenEXR", 0), 0u);
  EXPECT_EQ(error({{"c_texture", "ink.gif"}}), at + "c_texture: '" + dir +
                                                  "/ink.gif': unknown image format '.gif' (expected .png, .jpg, .bmp, .tga, "
                                                  ".hdr or .exr)");
  writePng("two.png", 2, 1, std::vector<unsigned char>(8, 255));
  writePng("three.png", 3, 1, std::vector<unsigned char>(12, 255));
  EXPECT_EQ(error({{"c_texture", {{"file", "two.png"}, {"channel", "x"}}}}),
            at + "c_texture/channel: unknown channel 'x' (mean, luminance, r, g, b, a)");
  EXPECT_EQ(error({{"c_texture", 3}}),
            at + "c_texture: expected an image file name or a texture object ({\"file\": ...} or {\"type\": ...}), got number");
  // An RGB colour is a reflectance's texture only.
  EXPECT_EQ(error({{"c_texture", {{"file", "two.png"}, {"channel", "rgb"}}}}),
            at + "c_texture/channel: unknown channel 'rgb' (mean, luminance, r, g, b, a)");
  EXPECT_EQ(error({{"reflectance_texture", {{"file", "two.png"}, {"channel", "x"}}}}),
            at + "reflectance_texture/channel: unknown channel 'x' (mean, luminance, r, g, b, a, rgb)");
  EXPECT_EQ(error({{"reflectance_texture", {{"file", "two.png"}, {"channel", "rgb"}}}}), "no error");
  // Textures of one material may differ in size (each is filtered on its own grid).
  EXPECT_EQ(error({{"c_texture", "two.png"}, {"Q_texture", "three.png"}}), "no error");
}

// ---------------------------------------------------------------------------------------------
// Shapes' texture coordinates and rendering

std::string sceneJson(const std::string& paper, const std::string& shape) {
  return R"({
  "camera": {"position": [0.5, 0.5, 2], "look_at": [0.5, 0.5, 0], "up": [0, 1, 0], "fov": 30, "resolution": [16, 16]},
  "render": {"spp": 4, "max_depth": 4, "seed": 3},
  "materials": {"paper": )" + paper + R"(},
  "shapes": [)" + shape + R"(],
  "lights": [{"type": "point", "position": [0.5, 0.5, 1.5], "intensity": {"type": "box", "min": 380, "max": 460}, "scale": 5}]
})";
}
const std::string kRectangle = R"({"type": "rectangle", "corners": [[0,0,0], [2,0,0], [2,1,0], [0,1,0]], "material": "paper"})";
const std::string kJung = R"({"type": "jung_fluorescent", "absorption": {"type": "box", "min": 380, "max": 470, "value": 0.9},
  "emission": {"type": "box", "min": 500, "max": 560}, "reflectance": 0.7, "c": 0.8, "Q": 0.9)";

TEST_F(TextureFiles, RectangleSphereAndDiskTextureCoordinates) {
  writeText("rect.json", sceneJson(kJung + "}", kRectangle));
  const auto scene = loadScene(dir + "/rect.json");
  const std::optional<Hit> h = scene->accel->intersect(Ray{Vec3(1.5f, 0.25f, 1.0f), Vec3(0, 0, -1)});
  ASSERT_TRUE(h);
  EXPECT_NEAR(scene->uv(*h).x, 0.75f, 1e-5f);  // corners in order: (0,0), (1,0), (1,1), (0,1)
  EXPECT_NEAR(scene->uv(*h).y, 0.25f, 1e-5f);
  Shape sphere;
  sphere.kind = Shape::Kind::Sphere;
  EXPECT_NEAR(sphere.surfaceUv(0, Vec2(0), Vec3(0, 1, 0)).y, 1.0f, 1e-6f);
  EXPECT_NEAR(sphere.surfaceUv(0, Vec2(0), Vec3(0, -1, 0)).y, 0.0f, 1e-6f);
  EXPECT_NEAR(sphere.surfaceUv(0, Vec2(0), Vec3(-1, 0, 0)).x, 0.0f, 1e-6f);
  EXPECT_NEAR(sphere.surfaceUv(0, Vec2(0), Vec3(0, 0, 1)).x, 0.75f, 1e-6f);
  // Placed by a transform (a 90° turn about z, scale 2, a shift): its top is world −x, and the
  // point seen from +z is its own +z, u = 3/4; a transform that shears is an error.
  writeText("ball.json", sceneJson(kJung + "}", R"({"type": "sphere", "center": [0, 0, 0], "radius": 0.5,
    "material": "paper", "transform": [[0, -2, 0, 1], [2, 0, 0, 0], [0, 0, 2, 0], [0, 0, 0, 1]]})"));
  const auto ball = loadScene(dir + "/ball.json");
  const Shape& b = ball->shapes.at(0);
  EXPECT_NEAR(b.radius, 1.0f, 1e-6f);
  EXPECT_NEAR(b.center.x, 1.0f, 1e-6f);
  EXPECT_NEAR(b.surfaceUv(0, Vec2(0), Vec3(-1, 0, 0)).y, 1.0f, 1e-6f);
  EXPECT_NEAR(b.surfaceUv(0, Vec2(0), Vec3(0, 0, 1)).x, 0.75f, 1e-6f);
  writeText("sheared.json", sceneJson(kJung + "}", R"({"type": "sphere", "center": [0, 0, 0], "radius": 0.5,
    "material": "paper", "transform": [[1, 1, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]})"));
  EXPECT_THROW(loadScene(dir + "/sheared.json"), InputError);
  // The disk as Mitsuba's: u = radius, v = angle/2π, within what the 256-triangle fan's linear
  // interpolation allows: its chords (1 − cos(π/256)) and, towards the centre, whose one vertex
  // carries its triangle's middle angle, half a triangle's angle (1/512).
  writeText("disk.json", sceneJson(kJung + "}", R"({"type": "disk", "material": "paper"})"));
  const auto disk = loadScene(dir + "/disk.json");
  for (const float angle : {0.3f, 1.7f, 4.0f}) {
    const Vec3 p(0.5f * std::cos(angle), 0.5f * std::sin(angle), 1.0f);
    const std::optional<Hit> d = disk->accel->intersect(Ray{p, Vec3(0, 0, -1)});
    ASSERT_TRUE(d);
    EXPECT_NEAR(disk->uv(*d).x, 0.5f, 2e-4f) << angle;
    EXPECT_NEAR(disk->uv(*d).y, angle / (2.0f * kPi), 1.0f / 512.0f) << angle;
  }
}

TEST_F(TextureFiles, MeshWithoutTextureCoordinatesIsAnError) {
  writePng("one.png", 1, 1, {255, 255, 255, 255});
  writeText("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  writeText("mesh.json", sceneJson(kJung + R"(, "c_texture": "one.png"})",
                                   R"({"type": "mesh", "file": "tri.obj", "material": "paper"})"));
  try {
    loadScene(dir + "/mesh.json");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), dir + "/mesh.json: /shapes/0/material: material 'paper' is textured, but this "
                                           "mesh has no texture coordinates (vt)");
  }
  // With vt it loads, and the hit's uv interpolates them.
  writeText("tri_uv.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n");
  writeText("mesh_uv.json", sceneJson(kJung + R"(, "c_texture": "one.png"})",
                                      R"({"type": "mesh", "file": "tri_uv.obj", "material": "paper"})"));
  const auto scene = loadScene(dir + "/mesh_uv.json");
  const std::optional<Hit> h = scene->accel->intersect(Ray{Vec3(0.2f, 0.3f, 1.0f), Vec3(0, 0, -1)});
  ASSERT_TRUE(h);
  EXPECT_NEAR(scene->uv(*h).x, 0.2f, 1e-5f);
  EXPECT_NEAR(scene->uv(*h).y, 0.3f, 1e-5f);
  EXPECT_TRUE(scene->materials[0]->textured());
}

// A scene's textures count against `--memory-limit` (SceneLoadOptions::memoryLimit): the error
// names the scene, the field and the image.
TEST_F(TextureFiles, SceneMemoryLimit) {
  writePng("ink.png", 64, 64, std::vector<unsigned char>(64 * 64 * 4, 128));
  writeText("ink.json", sceneJson(kJung + R"(, "c_texture": "ink.png"})", kRectangle));
  SceneLoadOptions options;
  options.memoryLimit = 16 << 10;
  try {
    loadScene(dir + "/ink.json", options);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), dir + "/ink.json: /materials/paper/c_texture: " + dir +
                                         "/ink.png: decoding this texture (64×64 pixels) besides the scene's textures "
                                         "before it (0 bytes) needs 48.0 KiB, more than the memory limit of 16.0 KiB "
                                         "(raise it with --memory-limit)");
  }
  options.memoryLimit = 48 << 10;
  EXPECT_NO_THROW(loadScene(dir + "/ink.json", options));
}

// A constant texture is the untextured material: the same image, bit for bit, from the same seed.
// 0.5 is exact in half floats, so c = 0.8 × 0.5 is the float 0.4 of the plain material.
TEST_F(TextureFiles, ConstantTextureRendersAsTheUntexturedMaterial) {
  writePng("white.png", 2, 2, std::vector<unsigned char>(16, 255));
  writeExr("half.exr", 3, 3, std::vector<float>(9, 0.5f));
  writeText("plain.json", sceneJson(kJung + "}", kRectangle));
  writeText("white.json", sceneJson(kJung + R"(, "c_texture": "white.png", "reflectance_texture": "white.png"})", kRectangle));
  std::string half = kJung + R"(, "Q_texture": "half.exr"})";
  writeText("half.json", sceneJson(half, kRectangle));
  std::string plainHalf = kJung + "}";
  plainHalf.replace(plainHalf.find("\"Q\": 0.9"), 8, "\"Q\": 0.45");
  writeText("plain_half.json", sceneJson(plainHalf, kRectangle));
  for (const char* integ : {"pt", "lt", "bdpt-independent"}) {
    const std::vector<Vec3> plain = renderFilm(dir + "/plain.json", integ);
    double sum = 0.0;
    for (const Vec3& p : plain) sum += p.y;
    EXPECT_GT(sum, 0.0) << integ << ": the test scene is lit";
    EXPECT_EQ(renderFilm(dir + "/white.json", integ), plain) << integ;
    const std::vector<Vec3> h = renderFilm(dir + "/half.json", integ);
    EXPECT_EQ(h, renderFilm(dir + "/plain_half.json", integ)) << integ;
    EXPECT_NE(h, plain) << integ << ": Q is textured";
  }
}

// The shipped ink scene: ink and paper resolved at hits (texel centres, where bilinear filtering
// gives the texel).
TEST(FluorescentInkScene, InkAndPaperResolveAtHits) {
  const auto scene = loadScene(std::string(KASHA_SOURCE_DIR) + "/scenes/fluorescent_ink.json");
  ASSERT_EQ(scene->materials.size(), 2u);
  for (const auto& m : scene->materials) ASSERT_TRUE(m->textured());
  // Left sheet: the red channel's ring is centred on pixel (32, 32) of 128×64, radii 14–22, so
  // pixel (32 + 18, 32) is ink and the centre is paper. uv of a pixel centre: ((x + ½)/128, 1 − (y + ½)/64).
  const auto cAt = [&](float px, float py) {
    const float u = (px + 0.5f) / 128.0f, v = 1.0f - (py + 0.5f) / 64.0f;
    const Vec3 p(-0.45f + 0.4f * u, -0.1f + 0.2f * v, 1.0f);  // the left sheet spans 0.4 × 0.2
    const std::optional<Hit> h = scene->accel->intersect(Ray{p, Vec3(0, 0, -1)});
    EXPECT_TRUE(h);
    const Bsdf bsdf = scene->bsdf(*h, {});  // the per-hit model lives inside the Bsdf
    const auto* j = dynamic_cast<const JungModel*>(&bsdf.model());
    EXPECT_NE(j, nullptr);
    return j ? j->c() : -1.0f;
  };
  EXPECT_FLOAT_EQ(cAt(50.0f, 32.0f), 0.9f);
  EXPECT_FLOAT_EQ(cAt(32.0f, 32.0f), 0.0f);
}

}  // namespace
}  // namespace kasha
