// The checkerboard texture (core/checkerboard_texture.h) against the parity of its cells, with and
// without a to_uv transform, read through kasha's JSON; and roughness textures: a textured
// rough material evaluates at a hit exactly as the untextured material built with the texel's α.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/checkerboard_texture.h"
#include "core/error.h"
#include "core/rgb_spectrum.h"
#include "core/rng.h"
#include "materials/material_json.h"
#include "tests/material_support.h"

namespace kasha {
namespace {

std::unique_ptr<Material> material(const std::string& json) {
  return parseMaterial(nlohmann::json::parse(json), SpectrumContext{"scene.json", "."}, "/materials/m",
                       WavelengthRange{300.0f, 830.0f});
}

std::string parseError(const std::string& json) {
  try {
    material(json);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// Cell (i, j) = (floor(2s), floor(2t)) of the transformed coordinates: color0 where i + j is even
// (both halves below ½ or both above), color1 where it is odd.
bool evenCell(float s, float t) { return (int64_t(std::floor(2.0 * s)) + int64_t(std::floor(2.0 * t))) % 2 == 0; }

TEST(CheckerboardTexture, ValuesFollowTheCellParity) {
  const Vec3 c0(0.1f, 0.2f, 0.3f), c1(0.9f, 0.8f, 0.7f);
  UvTransform scale;  // u' = 15u + 0.25, v' = 15v (Mitsuba's <scale x="15" y="15"/> and a shift)
  scale.linear = glm::mat2(15.0f);
  scale.offset = Vec2(0.25f, 0.0f);
  const CheckerboardTexture plain(c0, c1, 3), scaled(c0, c1, 3, scale);
  Rng rng(7);
  for (int k = 0; k < 2000; ++k) {
    const Vec2 uv(rng.uniform() * 4.0f - 2.0f, rng.uniform() * 4.0f - 2.0f);
    const double s = 15.0 * uv.x + 0.25, t = 15.0 * uv.y;
    // Points too close to a cell edge for float rounding are skipped.
    if (std::abs(2.0 * s - std::round(2.0 * s)) < 1e-3 || std::abs(2.0 * t - std::round(2.0 * t)) < 1e-3) continue;
    EXPECT_EQ(plain.rgb({uv}), evenCell(uv.x, uv.y) ? c0 : c1) << uv.x << " " << uv.y;
    EXPECT_EQ(scaled.rgb({uv}), evenCell(float(s), float(t)) ? c0 : c1) << uv.x << " " << uv.y;
  }
  // The unit square's four quarters, as Mitsuba's docs draw them.
  EXPECT_EQ(plain.rgb({Vec2(0.25f, 0.25f)}), c0);
  EXPECT_EQ(plain.rgb({Vec2(0.75f, 0.75f)}), c0);
  EXPECT_EQ(plain.rgb({Vec2(0.75f, 0.25f)}), c1);
  EXPECT_EQ(plain.rgb({Vec2(0.25f, 0.75f)}), c1);
  // One channel: the value.
  const CheckerboardTexture scalar(Vec3(0.4f), Vec3(0.2f), 1);
  EXPECT_EQ(scalar.scalar({Vec2(0.1f, 0.1f)}), 0.4f);
  EXPECT_EQ(scalar.scalar({Vec2(0.6f, 0.1f)}), 0.2f);
}

// In JSON: the defaults 0.4 / 0.2, colours on reflectances, to_uv as two rows; a Lambertian reads
// the cell's value.
TEST(CheckerboardTexture, JsonOnAReflectance) {
  const Vec3 n(0.0f, 0.0f, 1.0f);
  const auto reflectance = [&](const Material& m, Vec2 uv, float lambda) {
    return test::localBsdf(m, lambda, uv).eval({TransportMode::Radiance, SpectralLobe::Elastic, lambda, lambda}, n, n) *
           kPi;
  };
  const auto grey = material(R"({"type": "lambertian", "reflectance": 1, "reflectance_texture": {"type": "checkerboard"}})");
  EXPECT_FLOAT_EQ(reflectance(*grey, Vec2(0.2f, 0.3f), 550.0f), 0.4f);
  EXPECT_FLOAT_EQ(reflectance(*grey, Vec2(0.7f, 0.3f), 550.0f), 0.2f);
  // to_uv [[2, 0, 0], [0, 1, 0]]: u = 0.3 → 0.6, in the second column.
  const auto scaled = material(R"({"type": "lambertian", "reflectance": 1,
      "reflectance_texture": {"type": "checkerboard", "color0": 0.5, "color1": 0.25, "to_uv": [[2, 0, 0], [0, 1, 0]]}})");
  EXPECT_FLOAT_EQ(reflectance(*scaled, Vec2(0.3f, 0.3f), 550.0f), 0.25f);
  EXPECT_FLOAT_EQ(reflectance(*scaled, Vec2(0.2f, 0.3f), 550.0f), 0.5f);
  // A colour: its Jakob–Hanika spectrum.
  const auto colour = material(R"({"type": "lambertian", "reflectance": 1,
      "reflectance_texture": {"type": "checkerboard", "color0": [0.8, 0.3, 0.1], "color1": 0.2}})");
  const RgbSigmoid s = rgbToSigmoid(Vec3(0.8f, 0.3f, 0.1f)), g = rgbToSigmoid(Vec3(0.2f));
  for (float l : {450.0f, 550.0f, 650.0f}) {
    EXPECT_NEAR(reflectance(*colour, Vec2(0.1f, 0.1f), l), s(l), 1e-6f);
    EXPECT_NEAR(reflectance(*colour, Vec2(0.6f, 0.1f), l), g(l), 1e-6f);
  }
  // Errors in one line naming the field.
  EXPECT_NE(parseError(R"({"type": "lambertian", "reflectance": 1, "reflectance_texture": {"type": "checkerboard", "color0": 1.5}})")
                .find("/materials/m/reflectance_texture/color0: values must lie in [0, 1]"),
            std::string::npos);
  EXPECT_NE(parseError(R"({"type": "rough_conductor", "reflectance": 1, "alpha": 1, "alpha_texture": {"type": "checkerboard", "color0": [0.1, 0.2, 0.3]}})")
                .find("color0: expected a number (a scalar parameter's texture)"),
            std::string::npos);
  EXPECT_NE(parseError(R"({"type": "lambertian", "reflectance": 1, "reflectance_texture": {"type": "checkerboard", "to_uv": [[1, 0], [0, 1]]}})")
                .find("to_uv: expected two rows of three finite numbers"),
            std::string::npos);
  EXPECT_NE(parseError(R"({"type": "lambertian", "reflectance": 1, "reflectance_texture": {"type": "noise"}})")
                .find("unknown texture type 'noise' (image, checkerboard, mesh_attribute)"),
            std::string::npos);
}

// f of `m` at uv for a few direction pairs, in both transport modes.
std::vector<float> evals(const Material& m, Vec2 uv) {
  std::vector<float> out;
  const float lambda = 550.0f;
  const Bsdf b = test::localBsdf(m, lambda, uv);
  for (const Vec3& wi : {glm::normalize(Vec3(0.3f, 0.2f, 0.9f)), glm::normalize(Vec3(-0.6f, 0.1f, 0.4f))})
    for (const Vec3& wo : {glm::normalize(Vec3(-0.2f, -0.1f, 0.9f)), glm::normalize(Vec3(0.5f, -0.4f, 0.3f)),
                           glm::normalize(Vec3(0.1f, 0.3f, -0.8f))})
      for (const TransportMode mode : {TransportMode::Radiance, TransportMode::Importance})
        out.push_back(b.eval({mode, SpectralLobe::Elastic, lambda, lambda}, wi, wo));
  return out;
}

// Textured roughness (α = 1 times the texel, as the Mitsuba import writes it) evaluates as the
// untextured material with the texel's α, isotropic and per axis, for the three rough kinds.
TEST(TexturedRoughness, EvaluatesAsTheUntexturedMaterialWithTheTexelsAlpha) {
  const std::string checker = R"({"type": "checkerboard", "color0": 0.3, "color1": 0.6})";
  const Vec2 cell0(0.2f, 0.2f), cell1(0.7f, 0.2f);
  struct Case {
    std::string textured, at0, at1;
  };
  const std::vector<Case> cases = {
      {R"({"type": "rough_conductor", "reflectance": 0.9, "alpha": 1, "alpha_texture": )" + checker + "}",
       R"({"type": "rough_conductor", "reflectance": 0.9, "alpha": 0.3})",
       R"({"type": "rough_conductor", "reflectance": 0.9, "alpha": 0.6})"},
      {R"({"type": "rough_dielectric", "ior": 1.5, "alpha": 1, "alpha_texture": )" + checker + "}",
       R"({"type": "rough_dielectric", "ior": 1.5, "alpha": 0.3})", R"({"type": "rough_dielectric", "ior": 1.5, "alpha": 0.6})"},
      {R"({"type": "coated_fluorescent", "absorption": 0, "emission": 1, "reflectance": 0.5, "c": 0, "Q": 0,
           "coat_ior": 1.5, "coat_alpha": 1, "coat_alpha_texture": )" + checker + "}",
       R"({"type": "coated_fluorescent", "absorption": 0, "emission": 1, "reflectance": 0.5, "c": 0, "Q": 0,
           "coat_ior": 1.5, "coat_alpha": 0.3})",
       R"({"type": "coated_fluorescent", "absorption": 0, "emission": 1, "reflectance": 0.5, "c": 0, "Q": 0,
           "coat_ior": 1.5, "coat_alpha": 0.6})"},
      // Per axis: α_x untextured (0.2), α_y = 1 × the texel.
      {R"({"type": "rough_conductor", "reflectance": 0.9, "alpha": [0.2, 1], "alpha_texture": [null, )" + checker + "]}",
       R"({"type": "rough_conductor", "reflectance": 0.9, "alpha": [0.2, 0.3]})",
       R"({"type": "rough_conductor", "reflectance": 0.9, "alpha": [0.2, 0.6]})"}};
  for (const Case& c : cases) {
    const auto textured = material(c.textured), plain0 = material(c.at0), plain1 = material(c.at1);
    ASSERT_TRUE(textured->textured());
    EXPECT_EQ(evals(*textured, cell0), evals(*plain0, cell0)) << c.textured;
    EXPECT_EQ(evals(*textured, cell1), evals(*plain1, cell1)) << c.textured;
    EXPECT_NE(evals(*textured, cell0), evals(*textured, cell1)) << c.textured;
  }
  EXPECT_NE(parseError(R"({"type": "rough_conductor", "reflectance": 1, "alpha": 1, "alpha_texture": [null]})")
                .find("alpha_texture: expected one texture (both axes) or two"),
            std::string::npos);
}

}  // namespace
}  // namespace kasha
