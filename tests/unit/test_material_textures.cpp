// Textures on every material parameter (materials/surface_texture.h, textured_material.h): a
// constant image renders bit for bit as the untextured material (for every kind that takes
// textures, in pt, lt and BDPT), the per-hit model lives in the Bsdf and survives copies, an RGB
// reflectance is the Jakob–Hanika spectrum, filtering is bilinear unless nearest is asked for,
// and the per-hit models of the glossy kinds pass the direction χ² test.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "materials/jung_bbrrdf.h"
#include "materials/material_json.h"
#include "tests/glossy_support.h"
#include "tests/material_support.h"
#include "tests/support.h"
#include "tests/texture_files.h"

namespace kasha {
namespace {

using test::renderFilm;

class MaterialTextures : public test::TextureFiles {
 protected:
  MaterialTextures() : TextureFiles("material_textures") {}

  // A 16×16 view of the material on a tilted square beside a grey wall, lit by a point light
  // with UV and visible light (so that fluorescence, gloss and refraction all show).
  std::string scene(const std::string& name, const std::string& material) {
    return writeText(name, R"({
  "wavelength_range": [300, 830],
  "camera": {"position": [0.5, 0.5, 2], "look_at": [0.5, 0.5, 0], "up": [0, 1, 0], "fov": 40, "resolution": [16, 16]},
  "render": {"max_depth": 5},
  "materials": {"m": )" + material + R"(, "wall": {"type": "lambertian", "reflectance": 0.5}},
  "shapes": [{"type": "rectangle", "corners": [[0,0,0], [1,0,0.3], [1,1,0.3], [0,1,0]], "material": "m"},
             {"type": "rectangle", "corners": [[-1,-1,-0.5], [2,-1,-0.5], [2,2,-0.5], [-1,2,-0.5]], "material": "wall"}],
  "lights": [{"type": "point", "position": [0.8, 0.9, 1.2], "intensity": {"type": "box", "min": 340, "max": 700}, "scale": 5}]
})");
  }

  // {base, texture fields} → base with each field set to `file`.
  static std::string with(std::string base, const std::vector<std::string>& fields, const std::string& file) {
    base.pop_back();  // the closing brace
    for (const std::string& f : fields) base += ", \"" + f + "\": \"" + file + "\"";
    return base + "}";
  }
};

struct Kind {
  std::string name, json;
  std::vector<std::string> textures;  // every texture field it takes
  std::string halfField, halfFrom, halfTo;  // half.exr on halfField ≡ replacing halfFrom by halfTo
};

// Pixels whose XYZ differ in any bit.
int differing(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  int n = 0;
  for (size_t i = 0; i < a.size(); ++i) n += a[i] != b[i];
  return n;
}

std::vector<Kind> kinds() {
  const std::string fluor = R"("absorption": {"type": "box", "min": 330, "max": 470, "value": 0.9},
    "emission": {"type": "box", "min": 500, "max": 560}, "reflectance": 0.7, "c": 0.8, "Q": 0.9)";
  const std::string postit = test::sourcePath("scenes/spectra/bispectral_pink_postit_labsphere.csv");
  return {
      {"lambertian", R"({"type": "lambertian", "reflectance": 0.7})", {"reflectance_texture"}, "reflectance_texture",
       "\"reflectance\": 0.7", "\"reflectance\": 0.35"},
      {"mirror", R"({"type": "mirror", "reflectance": 0.9})", {"reflectance_texture"}, "reflectance_texture",
       "\"reflectance\": 0.9", "\"reflectance\": 0.45"},
      {"rough_conductor", R"({"type": "rough_conductor", "reflectance": 0.8, "alpha": 0.3})",
       {"reflectance_texture", "alpha_texture"}, "alpha_texture", "\"alpha\": 0.3", "\"alpha\": 0.15"},
      {"rough_dielectric", R"({"type": "rough_dielectric", "ior": 1.5, "alpha": 0.4})", {"alpha_texture"},
       "alpha_texture", "\"alpha\": 0.4", "\"alpha\": 0.2"},
      {"jung_fluorescent", R"({"type": "jung_fluorescent", )" + fluor + "}",
       {"reflectance_texture", "c_texture", "Q_texture"}, "c_texture", "\"c\": 0.8", "\"c\": 0.4"},
      {"coated_fluorescent", R"({"type": "coated_fluorescent", )" + fluor + R"(, "coat_ior": 1.5, "coat_alpha": 0.2})",
       {"reflectance_texture", "c_texture", "Q_texture", "coat_alpha_texture"}, "coat_alpha_texture",
       "\"coat_alpha\": 0.2", "\"coat_alpha\": 0.1"},
      {"zhdanov", R"({"type": "zhdanov", "gloss": 0.4, "gloss_exponent": 30, "passive": 0.3,
    "excitation": {"type": "box", "min": 330, "max": 470, "value": 0.2}, "emission": {"type": "box", "min": 500, "max": 560}})",
       {"gloss_texture", "gloss_exponent_texture", "passive_texture", "excitation_texture"}, "gloss_exponent_texture",
       "\"gloss_exponent\": 30", "\"gloss_exponent\": 15"},
      {"measured_reradiation", R"({"type": "measured_reradiation", "file": ")" + postit + "\"}",
       {"reflectance_texture", "reradiation_texture"}, "", "", ""},
  };
}

// A constant texture is the untextured material: the same image, bit for bit, from the same seed.
// White (1) on every field; 0.5 (exact in half floats) on one scalar equals the plain material
// with that parameter halved (halving is exact in floats), and changes the image (path tracing
// sees every kind).
TEST_F(MaterialTextures, ConstantTexturesRenderAsTheUntexturedMaterial) {
  writePng("white.png", 2, 2, std::vector<unsigned char>(16, 255));
  writeExr("half.exr", 3, 3, std::vector<float>(9, 0.5f));
  for (const Kind& k : kinds()) {
    const std::string plain = scene(k.name + "_plain.json", k.json);
    const std::string white = scene(k.name + "_white.json", with(k.json, k.textures, "white.png"));
    std::string halved = k.json;
    if (!k.halfField.empty()) halved.replace(halved.find(k.halfFrom), k.halfFrom.size(), k.halfTo);
    const std::string plainHalf = scene(k.name + "_plain_half.json", halved);
    const std::string halfField = k.halfField.empty() ? k.textures.back() : k.halfField;
    const std::string half = scene(k.name + "_half.json", with(k.json, {halfField}, "half.exr"));
    for (const char* integ : {"pt", "lt", "bdpt-independent"}) {
      const std::string what = k.name + " " + integ;
      const std::vector<Vec3> p = renderFilm(plain, integ);
      double sum = 0.0;
      for (const Vec3& v : p) sum += v.y;
      ASSERT_GT(sum, 0.0) << what << ": the test scene is lit";
      EXPECT_EQ(differing(renderFilm(white, integ), p), 0) << what;
      const std::vector<Vec3> h = renderFilm(half, integ);
      if (std::string(integ) == "pt") EXPECT_GT(differing(h, p), 0) << what << ": " << halfField << " is used";
      if (!k.halfField.empty()) EXPECT_EQ(differing(h, renderFilm(plainHalf, integ)), 0) << what << ": " << k.halfField;
    }
  }
}

std::unique_ptr<Material> material(const std::string& json, const std::string& dir) {
  return parseMaterial(nlohmann::json::parse(json), SpectrumContext{"scene.json", dir}, "/materials/m",
                       WavelengthRange{300.0f, 830.0f});
}

// Material::textures() lists one texture per textured field of every kind (what the scene loader
// checks shapes against), and is empty exactly when textured() is false.
TEST_F(MaterialTextures, TexturesListEveryTexturedField) {
  const std::string checker = R"({"type": "checkerboard", "color0": 0.5, "color1": 0.25})";
  for (const Kind& k : kinds()) {
    const auto plain = material(k.json, dir);
    EXPECT_FALSE(plain->textured()) << k.name;
    EXPECT_TRUE(plain->textures().empty()) << k.name;
    std::string json = k.json;
    json.pop_back();
    for (const std::string& f : k.textures) json += ", \"" + f + "\": " + checker;
    const auto textured = material(json + "}", dir);
    EXPECT_TRUE(textured->textured()) << k.name;
    // A roughness's one texture is listed for both axes.
    size_t expected = k.textures.size();
    for (const std::string& f : k.textures) expected += f.ends_with("alpha_texture");
    EXPECT_EQ(textured->textures().size(), expected) << k.name;
  }
}

// A textured material's Bsdf carries its own model, and copies carry theirs; an untextured one
// points at the material.
TEST_F(MaterialTextures, PerHitModelLivesInTheBsdf) {
  writeExr("ramp.exr", 2, 1, {0.25f, 0.75f});
  const auto textured = material(R"({"type": "lambertian", "reflectance": 1, "reflectance_texture": "ramp.exr"})", dir);
  const auto plain = material(R"({"type": "lambertian", "reflectance": 1})", dir);
  const Vec3 wi = glm::normalize(Vec3(0.3f, 0.1f, 0.9f)), wo = glm::normalize(Vec3(-0.2f, 0.4f, 0.8f));
  const auto value = [&](const Bsdf& b) {
    return b.eval({TransportMode::Radiance, SpectralLobe::Elastic, 550.0f, 550.0f}, wi, wo) * kPi;
  };
  const auto inside = [](const Bsdf& b) {
    const auto* p = reinterpret_cast<const unsigned char*>(&b.model());
    const auto* o = reinterpret_cast<const unsigned char*>(&b);
    return p >= o && p < o + sizeof(Bsdf);
  };
  const Bsdf u = test::localBsdf(*plain);
  EXPECT_FALSE(inside(u));
  EXPECT_EQ(&u.model(), dynamic_cast<const BsdfModel*>(plain.get()));

  std::vector<Bsdf> copies;
  {
    const Bsdf left = test::localBsdf(*textured, 550.0f, Vec2(0.25f, 0.5f));   // texel 0's centre
    const Bsdf right = test::localBsdf(*textured, 550.0f, Vec2(0.75f, 0.5f));  // texel 1's centre
    EXPECT_TRUE(inside(left));
    EXPECT_FLOAT_EQ(value(left), 0.25f);
    EXPECT_FLOAT_EQ(value(right), 0.75f);
    copies.push_back(left);
    copies.push_back(right);
    Bsdf assigned = u;
    assigned = right;
    copies.push_back(assigned);
  }  // the originals are gone: the copies hold their models
  for (const Bsdf& b : copies) EXPECT_TRUE(inside(b));
  EXPECT_FLOAT_EQ(value(copies[0]), 0.25f);
  EXPECT_FLOAT_EQ(value(copies[1]), 0.75f);
  EXPECT_FLOAT_EQ(value(copies[2]), 0.75f);
  copies.resize(100, copies[0]);  // reallocation copies them again
  EXPECT_FLOAT_EQ(value(copies[99]), 0.25f);
  EXPECT_FLOAT_EQ(value(copies[1]), 0.75f);
}

// Bilinear by default: halfway between two texel centres is the mean; "nearest" takes the texel.
TEST_F(MaterialTextures, BilinearByDefaultNearestOnRequest) {
  writeExr("ramp.exr", 2, 1, {0.25f, 0.75f});
  const std::string jung = R"({"type": "jung_fluorescent", "absorption": 0.5, "emission": 1, "reflectance": 0.5,
    "c": 1, "Q": 1, "c_texture": )";
  const auto bilinear = material(jung + R"("ramp.exr"})", dir);
  const auto nearest = material(jung + R"({"file": "ramp.exr", "filter": "nearest"}})", dir);
  const auto c = [](const Material& m, float u) {
    return dynamic_cast<const JungModel&>(test::localBsdf(m, 550.0f, Vec2(u, 0.5f)).model()).c();
  };
  EXPECT_FLOAT_EQ(c(*bilinear, 0.5f), 0.5f);
  EXPECT_FLOAT_EQ(c(*bilinear, 0.375f), 0.375f);
  EXPECT_FLOAT_EQ(c(*nearest, 0.45f), 0.25f);
  EXPECT_FLOAT_EQ(c(*nearest, 0.55f), 0.75f);
}

// An RGB reflectance texture multiplies the spectrum by the colour's Jakob–Hanika spectrum.
TEST_F(MaterialTextures, RgbReflectanceIsTheJakobHanikaSpectrum) {
  writePng("orange.png", 1, 1, {230, 120, 40, 255});
  const Vec3 rgb(230.0f / 255.0f, 120.0f / 255.0f, 40.0f / 255.0f);
  const RgbSigmoid s = rgbToSigmoid(rgb);
  const auto m = material(
      R"({"type": "lambertian", "reflectance": 0.5, "reflectance_texture": {"file": "orange.png", "channel": "rgb"}})", dir);
  const Bsdf b = test::localBsdf(*m, 550.0f, Vec2(0.3f, 0.6f));
  const Vec3 w(0.0f, 0.0f, 1.0f);
  for (float l = 300.0f; l <= 830.0f; l += 10.0f) {
    const float r = b.eval({TransportMode::Radiance, SpectralLobe::Elastic, l, l}, w, w) * kPi;
    EXPECT_NEAR(r, 0.5f * s(l), 1e-6f) << l;
    EXPECT_GE(r, 0.0f);
    EXPECT_LE(r, 0.5f);
  }
  // The colour comes back under D65 (the table's accuracy, core/rgb_spectrum.h).
  std::vector<float> ls, vs;
  for (float l = 360.0f; l <= 830.0f; l += 1.0f) ls.push_back(l), vs.push_back(s(l));
  const Vec3 back = reflectanceToLinearSrgb(Spectrum::piecewiseLinear(ls, vs));
  EXPECT_NEAR(back.x, rgb.x, 0.01f);
  EXPECT_NEAR(back.y, rgb.y, 0.01f);
  EXPECT_NEAR(back.z, rgb.z, 0.01f);
}

// The per-hit models of the glossy kinds, at a hit where the texture blends two texels (0.35),
// sample directions with the density they report (docs/validation.md §3), in both modes (elastic only:
// no fluorescence, as directionChi2 bins the elastic density).
TEST_F(MaterialTextures, TexturedGlossyModelsPassChi2) {
  writeExr("ramp.exr", 2, 1, {0.25f, 0.75f});
  const std::vector<std::string> materials = {
      R"({"type": "rough_conductor", "reflectance": 0.8, "alpha": 0.6, "alpha_texture": "ramp.exr"})",
      R"({"type": "rough_dielectric", "ior": 1.5, "alpha": 0.7, "alpha_texture": "ramp.exr"})",
      R"({"type": "coated_fluorescent", "absorption": 0.5, "emission": 1, "reflectance": 0.6, "c": 0, "Q": 0.5,
          "coat_ior": 1.5, "coat_alpha": 0.5, "coat_alpha_texture": "ramp.exr", "reflectance_texture": "ramp.exr"})",
      R"({"type": "zhdanov", "gloss": 0.5, "gloss_exponent": 40, "passive": 0.4, "excitation": 0, "emission": 1,
          "gloss_texture": "ramp.exr", "gloss_exponent_texture": "ramp.exr"})"};
  test::DirectionChi2Config config;
  config.uv = Vec2(0.4f, 0.5f);
  config.samples = 100000;
  uint64_t seed = 1;
  for (const std::string& json : materials) {
    const auto m = material(json, dir);
    for (const TransportMode mode : {TransportMode::Radiance, TransportMode::Importance})
      for (const Vec3& w : {glm::normalize(Vec3(0.3f, 0.2f, 0.9f)), glm::normalize(Vec3(-0.7f, 0.1f, 0.3f))}) {
        const test::DirectionChi2Result r = test::directionChi2(*m, mode, w, 550.0f, seed++, config);
        EXPECT_GT(r.p, 1e-3) << m->describe() << " " << toString(mode);
      }
  }
}

}  // namespace
}  // namespace kasha
