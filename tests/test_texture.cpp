// Textures (core/texture.h), texture coordinates of shapes (core/shape.h) and the textured Jung
// material (materials/textured_jung.h): lookup, files, errors, and that a textured material with a
// constant image renders exactly as the untextured one.
#include <gtest/gtest.h>
#include <unistd.h>

#include <ImfRgbaFile.h>
#include <png.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "scene/scene_loader.h"
#include "core/texture.h"
#include "integrators/integrator_factory.h"
#include "integrators/render_loop.h"
#include "materials/jung_bbrrdf.h"
#include "materials/material_json.h"
#include "materials/textured_jung.h"

namespace kasha {
namespace {

namespace fs = std::filesystem;

class TextureFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = (fs::path(::testing::TempDir()) / ("kasha_texture." + std::to_string(getpid()))).string();
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }

  // RGBA bytes, row 0 at the top.
  std::string writePng(const std::string& name, int w, int h, const std::vector<unsigned char>& rgba) {
    png_image img{};
    img.version = PNG_IMAGE_VERSION;
    img.width = png_uint_32(w);
    img.height = png_uint_32(h);
    img.format = PNG_FORMAT_RGBA;
    const std::string path = dir + "/" + name;
    EXPECT_TRUE(png_image_write_to_file(&img, path.c_str(), 0, rgba.data(), 0, nullptr)) << img.message;
    return path;
  }
  // One grey value per pixel (R = G = B, A = 1), row 0 at the top.
  std::string writeExr(const std::string& name, int w, int h, const std::vector<float>& grey) {
    std::vector<Imf::Rgba> px;
    for (const float g : grey) px.emplace_back(g, g, g, 1.0f);
    const std::string path = dir + "/" + name;
    Imf::RgbaOutputFile out(path.c_str(), w, h, Imf::WRITE_RGBA);
    out.setFrameBuffer(px.data(), 1, size_t(w));
    out.writePixels(h);
    return path;
  }
  std::string writeText(const std::string& name, const std::string& text) {
    std::ofstream(dir + "/" + name) << text;
    return dir + "/" + name;
  }

  std::string dir;
};

// ---------------------------------------------------------------------------------------------
// Lookup

TEST(TextureLookup, NearestTexelOrientationAndRepeat) {
  // 3×2: row 0 (top) = 0.1 0.2 0.3, row 1 (bottom) = 0.4 0.5 0.6
  const ScalarTexture t(3, 2, {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f});
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) {
      const Vec2 centre((x + 0.5f) / 3.0f, 1.0f - (y + 0.5f) / 2.0f);
      const float expect = 0.1f * float(1 + x + 3 * y);
      EXPECT_FLOAT_EQ(t.lookup(centre), expect) << x << ", " << y;
      // Anywhere inside the texel, and repeated by whole periods in both directions.
      EXPECT_FLOAT_EQ(t.lookup(centre + Vec2(0.16f, -0.24f)), expect);
      EXPECT_FLOAT_EQ(t.lookup(centre + Vec2(2.0f, -3.0f)), expect);
      EXPECT_FLOAT_EQ(t.lookup(centre + Vec2(-1.0f, 5.0f)), expect);
    }
  EXPECT_FLOAT_EQ(t.lookup(Vec2(0.0f, 0.0f)), 0.4f) << "(0, 0) is the bottom-left corner";
  EXPECT_FLOAT_EQ(t.lookup(Vec2(0.999f, 0.999f)), 0.3f) << "(1, 1) is the top-right corner";
  EXPECT_FLOAT_EQ(t.lookup(Vec2(std::nanf(""), 0.7f)), t.lookup(Vec2(0.0f))) << "non-finite uv: no crash";
}

// ---------------------------------------------------------------------------------------------
// Files

TEST_F(TextureFiles, PngChannelsAreDataValues) {
  // 2×1: (255, 0, 51, 255) (0, 102, 204, 0)
  const std::string p = writePng("a.png", 2, 1, {255, 0, 51, 255, 0, 102, 204, 0});
  const auto at = [&](TextureChannel c, int x) { return ScalarTexture::load(p, c).lookup(Vec2((x + 0.5f) / 2, 0.5f)); };
  EXPECT_FLOAT_EQ(at(TextureChannel::R, 0), 1.0f);
  EXPECT_FLOAT_EQ(at(TextureChannel::G, 1), 0.4f);
  EXPECT_FLOAT_EQ(at(TextureChannel::B, 0), 0.2f);
  EXPECT_FLOAT_EQ(at(TextureChannel::A, 1), 0.0f);
  EXPECT_FLOAT_EQ(at(TextureChannel::Mean, 1), (0.0f + 0.4f + 0.8f) / 3.0f);
  EXPECT_EQ(ScalarTexture::load(p, TextureChannel::R).width(), 2);
}

TEST_F(TextureFiles, ExrValuesAndRange) {
  const std::string p = writeExr("a.exr", 2, 2, {0.0f, 0.25f, 0.5f, 1.0f});
  const ScalarTexture t = ScalarTexture::load(p, TextureChannel::Mean);
  EXPECT_FLOAT_EQ(t.lookup(Vec2(0.75f, 0.75f)), 0.25f);
  EXPECT_FLOAT_EQ(t.lookup(Vec2(0.25f, 0.25f)), 0.5f);
  const std::string bad = writeExr("bad.exr", 2, 1, {0.5f, 1.5f});
  try {
    ScalarTexture::load(bad, TextureChannel::Mean);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "value 1.500000 at pixel (1, 0) is outside [0, 1]");
  }
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
  EXPECT_EQ(error({{"c_texture", "ink.jpg"}}),
            at + "c_texture: '" + dir + "/ink.jpg': unknown image format '.jpg' (expected .png or .exr)");
  writePng("two.png", 2, 1, std::vector<unsigned char>(8, 255));
  writePng("three.png", 3, 1, std::vector<unsigned char>(12, 255));
  EXPECT_EQ(error({{"c_texture", {{"file", "two.png"}, {"channel", "x"}}}}),
            at + "c_texture/channel: unknown channel 'x' (mean, r, g, b, a)");
  EXPECT_EQ(error({{"c_texture", 3}}),
            at + "c_texture: expected an image file name or {\"file\": ..., \"channel\": ...}, got number");
  EXPECT_EQ(error({{"c_texture", "two.png"}, {"Q_texture", "three.png"}}),
            at + "Q_texture: 3×1 pixels, but c_texture has 2×1 (the textures of one material must have the same size)");
  // More distinct (c, Q) combinations than the palette holds: 65×64 different (R, G) pairs.
  std::vector<unsigned char> pairs;
  for (int i = 0; i < 65 * 64; ++i) pairs.insert(pairs.end(), {(unsigned char)(i % 256), (unsigned char)(i / 256), 0, 255});
  writePng("pairs.png", 65, 64, pairs);
  EXPECT_EQ(error({{"c_texture", {{"file", "pairs.png"}, {"channel", "r"}}}, {"Q_texture", {{"file", "pairs.png"}, {"channel", "g"}}}}),
            at + "c_texture: more than 4096 distinct combinations of texture values (quantise the images)");
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

TEST_F(TextureFiles, RectangleAndSphereTextureCoordinates) {
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

std::vector<Vec3> renderFilm(const std::string& path, const std::string& integratorName) {
  const auto scene = loadScene(path);
  const std::unique_ptr<Integrator> integrator = makeIntegrator(integratorName, *scene, scene->render);
  Film film(scene->camera.width(), scene->camera.height());
  RenderOptions opt;
  opt.spp = 4;
  opt.seed = 5;
  render(*scene, *integrator, film, opt);
  std::vector<Vec3> px;
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) px.push_back(film.xyz(x, y));
  return px;
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

// The shipped ink scene: two palette entries per sheet (ink, paper), resolved at hits.
TEST(FluorescentInkScene, InkAndPaperResolveAtHits) {
  const auto scene = loadScene(std::string(KASHA_SOURCE_DIR) + "/scenes/fluorescent_ink.json");
  ASSERT_EQ(scene->materials.size(), 2u);
  for (const auto& m : scene->materials) {
    ASSERT_TRUE(m->textured());
    EXPECT_EQ(static_cast<const TexturedJung&>(*m).paletteSize(), 2u);
  }
  // Left sheet: the red channel's ring is centred on pixel (32, 32) of 128×64, radii 14–22, so
  // pixel (32 + 18, 32) is ink and the centre is paper. uv of a pixel centre: ((x + ½)/128, 1 − (y + ½)/64).
  const auto cAt = [&](float px, float py) {
    const float u = (px + 0.5f) / 128.0f, v = 1.0f - (py + 0.5f) / 64.0f;
    const Vec3 p(-0.45f + 0.4f * u, -0.1f + 0.2f * v, 1.0f);  // the left sheet spans 0.4 × 0.2
    const std::optional<Hit> h = scene->accel->intersect(Ray{p, Vec3(0, 0, -1)});
    EXPECT_TRUE(h);
    const auto* j = dynamic_cast<const JungBbrrdf*>(&scene->bsdf(*h, {}).model());
    EXPECT_NE(j, nullptr);
    return j ? j->c() : -1.0f;
  };
  EXPECT_FLOAT_EQ(cAt(50.0f, 32.0f), 0.9f);
  EXPECT_FLOAT_EQ(cAt(32.0f, 32.0f), 0.0f);
}

}  // namespace
}  // namespace kasha
