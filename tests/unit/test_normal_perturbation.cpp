// Normal and bump maps (materials/normal_perturbation.h) on a rectangle whose tangents are known:
// corners (0,0,0) (2,0,0) (2,1,0) (0,1,0) with uv (0,0) (1,0) (1,1) (0,1), so ∂p/∂u = (2, 0, 0),
// ∂p/∂v = (0, 1, 0) and the tangent frame is the world's. A flat map leaves the nested material
// as it is (bit for bit, rendered); a constant tilted normal map and a linear height ramp give the
// nested material's Bsdf with the shading normal computed here by hand, through the shading-normal
// path (HitContext::shading) directly. Also the bilinear texture's gradient and the uv tangents.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "materials/normal_perturbation.h"
#include "tests/texture_files.h"

namespace kasha {
namespace {

class NormalPerturbation : public test::TextureFiles {
 protected:
  NormalPerturbation() : TextureFiles("normal_perturbation") {}

  // A scene with the rectangle above made of `material`, seen from above and lit from above.
  std::string scene(const std::string& name, const std::string& material) {
    return writeText(name, R"({
  "camera": {"position": [1, 0.5, 2], "look_at": [1, 0.5, 0], "up": [0, 1, 0], "fov": 40, "resolution": [12, 12]},
  "render": {"spp": 4, "max_depth": 3, "seed": 3},
  "materials": {"m": )" + material + R"(},
  "shapes": [{"type": "rectangle", "corners": [[0,0,0], [2,0,0], [2,1,0], [0,1,0]], "material": "m"}],
  "lights": [{"type": "point", "position": [1.4, 0.3, 1.5], "intensity": 1, "scale": 5}]
})");
  }
};

const std::string kGlossy = R"({"type": "rough_conductor", "reflectance": 0.8, "alpha": 0.3})";

// The Bsdf of the scene's material where the ray down through (x, y) hits the rectangle.
Bsdf bsdfAt(const Scene& s, float x, float y, const float& lambda, Hit* hit = nullptr) {
  const std::optional<Hit> h = s.accel->intersect(Ray{Vec3(x, y, 1.0f), Vec3(0, 0, -1)});
  EXPECT_TRUE(h);
  if (hit) *hit = *h;
  return s.bsdf(*h, {&lambda, 1});
}

// f of both Bsdfs for world directions, in both transport modes, agree within `rel`.
void expectSameScattering(const Bsdf& a, const Bsdf& b, float lambda, double rel) {
  const Vec3 dirs[] = {glm::normalize(Vec3(0.3f, -0.2f, 1.0f)), glm::normalize(Vec3(-0.5f, 0.1f, 0.8f)),
                       glm::normalize(Vec3(0.1f, 0.6f, 0.7f)), glm::normalize(Vec3(-0.2f, -0.4f, 0.9f))};
  int nonzero = 0;
  for (const TransportMode mode : {TransportMode::Radiance, TransportMode::Importance})
    for (const Vec3& wi : dirs)
      for (const Vec3& wo : dirs) {
        const float fa = a.eval({mode, SpectralLobe::Elastic, lambda, lambda}, a.toLocal(wi), a.toLocal(wo));
        const float fb = b.eval({mode, SpectralLobe::Elastic, lambda, lambda}, b.toLocal(wi), b.toLocal(wo));
        EXPECT_NEAR(fa, fb, rel * std::max(fa, fb)) << "wi " << wi.x << " " << wi.y << ", wo " << wo.x << " " << wo.y;
        nonzero += fa > 0.0f;
      }
  EXPECT_GT(nonzero, 8);
}

TEST(TextureGradient, BilinearGradientOfALinearFunctionIsExact) {
  // f = 0.1 + 0.05·x + 0.1·y in texel units (y up): ∂f/∂u = 0.05·w, ∂f/∂v = 0.1·h.
  const int w = 5, h = 4;
  std::vector<float> texels;
  for (int row = 0; row < h; ++row)
    for (int x = 0; x < w; ++x) texels.push_back(0.1f + 0.05f * float(x) + 0.1f * float(h - 1 - row));
  const ImageTexture t(w, h, 1, texels, TextureWrap::Clamp, TextureFilter::Bilinear);
  for (const Vec2 uv : {Vec2(0.3f, 0.4f), Vec2(0.55f, 0.71f), Vec2(0.2f, 0.3f)}) {
    const Vec2 g = t.scalarGradient(uv);
    EXPECT_NEAR(g.x, 0.05f * w, 1e-5f);
    EXPECT_NEAR(g.y, 0.1f * h, 1e-5f);
    // And it is the derivative of scalar(): a central difference.
    const float e = 1e-3f;
    EXPECT_NEAR(g.x, (t.scalar(uv + Vec2(e, 0)) - t.scalar(uv - Vec2(e, 0))) / (2 * e), 2e-3f);
  }
  const ImageTexture nearest(w, h, 1, texels, TextureWrap::Clamp, TextureFilter::Nearest);
  EXPECT_EQ(nearest.scalarGradient(Vec2(0.3f, 0.4f)), Vec2(0.0f));
}

TEST_F(NormalPerturbation, UvTangentsOfTrianglesAndSpheres) {
  const auto s = loadScene(scene("plain.json", kGlossy));
  Hit h;
  const float lambda = 550.0f;
  bsdfAt(*s, 0.7f, 0.2f, lambda, &h);
  const Shape::UvDerivatives d = s->shapes[0].uvDerivatives(h.prim, h.ng);
  EXPECT_NEAR(glm::length(d.dpdu - Vec3(2, 0, 0)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(d.dpdv - Vec3(0, 1, 0)), 0.0f, 1e-5f);
  // A sphere: the tangents are the derivatives of Shape::surfaceUv's inverse (central differences).
  Shape sphere;
  sphere.kind = Shape::Kind::Sphere;
  sphere.radius = 2.0f;
  const Vec3 n = glm::normalize(Vec3(0.3f, -0.4f, 0.5f));
  const Vec2 uv = sphere.surfaceUv(0, Vec2(0), n);
  const auto point = [&](Vec2 q) {  // u = ½ + φ/2π, v = θ/π with θ from −y
    const float phi = 2 * kPi * (q.x - 0.5f), theta = kPi * q.y;
    return sphere.radius * Vec3(std::sin(theta) * std::cos(phi), -std::cos(theta), std::sin(theta) * std::sin(phi));
  };
  EXPECT_NEAR(glm::length(point(uv) - sphere.radius * n), 0.0f, 1e-5f);
  const float e = 1e-3f;
  const Shape::UvDerivatives ds = sphere.uvDerivatives(0, n);
  EXPECT_NEAR(glm::length(ds.dpdu - (point(uv + Vec2(e, 0)) - point(uv - Vec2(e, 0))) / (2 * e)), 0.0f, 1e-2f);
  EXPECT_NEAR(glm::length(ds.dpdv - (point(uv + Vec2(0, e)) - point(uv - Vec2(0, e))) / (2 * e)), 0.0f, 1e-2f);
  // A cylinder, tilted, flipped inward: central differences of Cylinder::point at (u, 1 − v).
  Shape tube;
  tube.kind = Shape::Kind::Cylinder;
  tube.cylinder.frame = Frame::fromNormal(glm::normalize(Vec3(0.2f, 1.0f, -0.3f)));
  tube.cylinder.radius = 0.7f;
  tube.cylinder.length = 3.0f;
  tube.cylinder.inward = true;
  const Vec2 param(0.37f, 0.64f);
  const Vec2 tubeUv = tube.surfaceUv(0, param, tube.cylinder.normal(param));
  const auto tubePoint = [&](Vec2 q) { return tube.cylinder.point(Vec2(q.x, 1.0f - q.y)); };
  const Shape::UvDerivatives dc = tube.uvDerivatives(0, tube.cylinder.normal(param));
  EXPECT_NEAR(glm::length(dc.dpdu - (tubePoint(tubeUv + Vec2(e, 0)) - tubePoint(tubeUv - Vec2(e, 0))) / (2 * e)), 0.0f, 1e-2f);
  EXPECT_NEAR(glm::length(dc.dpdv - (tubePoint(tubeUv + Vec2(0, e)) - tubePoint(tubeUv - Vec2(0, e))) / (2 * e)), 0.0f, 1e-2f);
}

// A checkerboard height is constant in pieces: no slope, so the nested material's Bsdf as it is.
TEST_F(NormalPerturbation, CheckerboardHeightLeavesTheMaterialAsItIs) {
  const auto plain = loadScene(scene("plain.json", kGlossy));
  const auto bumped = loadScene(scene("checker_bump.json", R"({"type": "bump_map", "scale": 3,
    "height": {"type": "checkerboard", "color0": 0.9, "color1": 0.1}, "material": )" + kGlossy + "}"));
  const float lambda = 550.0f;
  expectSameScattering(bsdfAt(*bumped, 0.7f, 0.2f, lambda), bsdfAt(*plain, 0.7f, 0.2f, lambda), lambda, 0.0);
}

// rgb (½, ½, 1) is the unperturbed normal: the nested material renders exactly as it does alone.
TEST_F(NormalPerturbation, FlatNormalMapLeavesTheMaterialAsItIs) {
  writeRgbExr("flat.exr", 2, 2, std::vector<Vec3>(4, Vec3(0.5f, 0.5f, 1.0f)));
  writeExr("level.exr", 3, 1, std::vector<float>(3, 0.25f));
  const std::string plain = scene("plain.json", kGlossy);
  const std::string mapped = scene("mapped.json", R"({"type": "normal_map", "normals": "flat.exr", "material": )" + kGlossy + "}");
  const std::string bumped =
      scene("bumped.json", R"({"type": "bump_map", "height": "level.exr", "scale": 3, "material": )" + kGlossy + "}");
  for (const char* integ : {"pt", "lt"}) {
    const std::vector<Vec3> expect = test::renderFilm(plain, integ);
    double sum = 0.0;
    for (const Vec3& p : expect) sum += p.y;
    EXPECT_GT(sum, 0.0) << integ << ": the test scene is lit";
    EXPECT_EQ(test::renderFilm(mapped, integ), expect) << integ;
    EXPECT_EQ(test::renderFilm(bumped, integ), expect) << integ << ": a constant height";
  }
}

// A constant normal map tilting n to (¼, −¼, ¾) (normalised) in the tangent frame: the nested
// material with that shading normal.
TEST_F(NormalPerturbation, TiltedNormalMapIsTheShadingNormal) {
  writeRgbExr("tilt.exr", 2, 2, std::vector<Vec3>(4, Vec3(0.625f, 0.375f, 0.875f)));
  const auto s = loadScene(scene("tilt.json", R"({"type": "normal_map", "normals": "tilt.exr", "material": )" + kGlossy + "}"));
  const float lambda = 550.0f;
  Hit h;
  const Bsdf mapped = bsdfAt(*s, 0.7f, 0.2f, lambda, &h);
  const Vec3 n = glm::normalize(Vec3(0.25f, -0.25f, 0.75f));  // s = +x, t = +y, n = +z here
  EXPECT_NEAR(glm::length(mapped.toWorld(Vec3(0, 0, 1)) - n), 0.0f, 1e-6f);
  const auto& material = dynamic_cast<const PerturbedNormalMaterial&>(*s->materials[0]);
  const Frame geometric = Frame::fromNormal(h.ng);
  const Bsdf expect = material.nested().bsdf(HitContext{s->uv(h), geometric, Frame::fromNormal(n), {&lambda, 1}});
  expectSameScattering(mapped, expect, lambda, 1e-5);
  // And not the untilted material.
  const Bsdf flat = material.nested().bsdf(HitContext{s->uv(h), geometric, geometric, {&lambda, 1}});
  const Vec3 wi = glm::normalize(Vec3(0.3f, -0.2f, 1.0f)), wo = glm::normalize(Vec3(-0.5f, 0.1f, 0.8f));
  EXPECT_GT(std::abs(mapped.eval({TransportMode::Radiance, SpectralLobe::Elastic, lambda, lambda}, mapped.toLocal(wi),
                                 mapped.toLocal(wo)) -
                     flat.eval({TransportMode::Radiance, SpectralLobe::Elastic, lambda, lambda}, flat.toLocal(wi),
                               flat.toLocal(wo))),
            1e-3f);
}

// The height h = i/8 at the centres of 8 texels along u is h(u) = u − 1/16 between them, so the
// surface displaced by scale·h along z is z = scale·(x/2 − 1/16): its normal is ∝ (−scale/2, 0, 1).
TEST_F(NormalPerturbation, LinearHeightRampIsTheAnalyticTiltedNormal) {
  std::vector<float> ramp;
  for (int i = 0; i < 8; ++i) ramp.push_back(float(i) / 8.0f);
  writeExr("ramp.exr", 8, 1, ramp);
  const float scale = 0.5f;
  const auto s = loadScene(scene("ramp.json", R"({"type": "bump_map", "height": {"file": "ramp.exr", "wrap": "clamp"},
      "scale": 0.5, "material": )" + kGlossy + "}"));
  const float lambda = 550.0f;
  const auto& material = dynamic_cast<const PerturbedNormalMaterial&>(*s->materials[0]);
  const Vec3 n = glm::normalize(Vec3(-scale / 2.0f, 0.0f, 1.0f));
  for (const Vec2 xy : {Vec2(0.7f, 0.2f), Vec2(1.3f, 0.8f)}) {  // u = 0.35, 0.65: between texel centres
    Hit h;
    const Bsdf bumped = bsdfAt(*s, xy.x, xy.y, lambda, &h);
    EXPECT_NEAR(glm::length(bumped.toWorld(Vec3(0, 0, 1)) - n), 0.0f, 1e-5f);
    const Bsdf expect =
        material.nested().bsdf(HitContext{s->uv(h), Frame::fromNormal(h.ng), Frame::fromNormal(n), {&lambda, 1}});
    expectSameScattering(bumped, expect, lambda, 1e-4);
  }
}

TEST_F(NormalPerturbation, ClearErrors) {
  writeRgbExr("n.exr", 1, 1, {Vec3(0.5f, 0.5f, 1.0f)});
  const auto error = [&](const std::string& material) -> std::string {
    try {
      loadScene(scene("e.json", material));
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  const std::string at = dir + "/e.json: /materials/m/";
  EXPECT_EQ(error(R"({"type": "normal_map", "material": )" + kGlossy + "}"), at + "normals: missing required field");
  EXPECT_EQ(error(R"({"type": "normal_map", "normals": {"file": "n.exr", "channel": "r"}, "material": )" + kGlossy + "}"),
            at + "normals/channel: a normal map's channel is rgb");
  EXPECT_EQ(error(R"({"type": "bump_map", "height": "n.exr", "material": {"type": "glass"}})"),
            at + "material/type: unknown material type 'glass' (lambertian, jung_fluorescent, mirror, dielectric, "
                 "thin_dielectric, rough_conductor, rough_dielectric, coated_fluorescent, zhdanov, measured_reradiation, "
                 "normal_map, bump_map, mask, blend, file)");
  EXPECT_EQ(error(R"({"type": "bump_map", "height": "n.exr"})"), at + "material: missing required field");
  EXPECT_EQ(error(R"({"type": "normal_map", "normals": {"type": "checkerboard"}, "material": )" + kGlossy + "}"),
            at + "normals: a normal map needs three channels (a colour)");
  EXPECT_EQ(error(R"({"type": "bump_map", "height": {"type": "mesh_attribute", "name": "vertex_h"}, "material": )" +
                  kGlossy + "}"),
            at + "height: a height is read at texture coordinates (a mesh attribute has no slope)");
}

}  // namespace
}  // namespace kasha
