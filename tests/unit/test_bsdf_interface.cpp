// The per-hit Bsdf interface (materials/bsdf.h) for every material type, textured included:
// - the fluorescent-event probability is the material's own and equals 1 − the elastic lobe's
//   spectral density, in both modes over a grid of wavelengths, and is the frequency with which
//   sampleSpectral actually picks the fluorescent lobe (for every u below it);
// - the flags tell the truth: a direction density that depends on λ is flagged
//   WavelengthDependentDirection (hero wavelengths rely on it), and a material's flags contain
//   those of every Bsdf it builds;
// - every fluorescent material's FluorophoreSpectra cover what it absorbs and re-emits, so that
//   the wavelength strategies following fluorophores serve it without bias.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "core/rng.h"
#include "scene/scene_loader.h"
#include "tests/material_support.h"
#include "tests/support.h"

namespace kasha {
namespace {

const char* kAnalytic = R"({
  "camera": {"position": [0, 0, -3], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 40, "resolution": [4, 4]},
  "wavelength_range": [300, 830],
  "materials": {
    "lambertian": {"type": "lambertian", "reflectance": {"type": "tabulated", "wavelengths": [400, 700], "values": [0.2, 0.8]}},
    "mirror": {"type": "mirror", "reflectance": 0.9},
    "glass": {"type": "dielectric", "ior": "BK7"},
    "thin_glass": {"type": "thin_dielectric", "ior": "BK7"},
    "metal": {"type": "rough_conductor", "reflectance": {"type": "tabulated", "wavelengths": [400, 700], "values": [0.5, 0.9]}, "alpha": 0.3},
    "rough_glass": {"type": "rough_dielectric", "ior": "BK7", "alpha": 0.3},
    "rough_plain_glass": {"type": "rough_dielectric", "ior": 1.5, "alpha": 0.3},
    "jung": {"type": "jung_fluorescent", "absorption": {"type": "gaussian", "center": 420, "fwhm": 60, "peak": 0.9},
             "emission": {"type": "gaussian", "center": 520, "fwhm": 40}, "reflectance": 0.7, "c": 0.6, "Q": 0.8},
    "coated": {"type": "coated_fluorescent", "absorption": {"type": "gaussian", "center": 420, "fwhm": 60, "peak": 0.9},
               "emission": {"type": "gaussian", "center": 520, "fwhm": 40},
               "reflectance": {"type": "tabulated", "wavelengths": [400, 700], "values": [0.9, 0.1]}, "c": 0.5, "Q": 0.9,
               "coat_ior": "BK7", "coat_alpha": 0.1},
    "zhdanov": {"type": "zhdanov", "gloss": 0.3, "gloss_exponent": 40,
                "passive": {"type": "tabulated", "wavelengths": [400, 700], "values": [0.1, 0.5]},
                "excitation": {"type": "gaussian", "center": 400, "fwhm": 50, "peak": 0.3},
                "emission": {"type": "gaussian", "center": 560, "fwhm": 60}},
    "masked_jung": {"type": "mask", "opacity": 0.6, "material": {"type": "jung_fluorescent",
                    "absorption": {"type": "gaussian", "center": 420, "fwhm": 60, "peak": 0.9},
                    "emission": {"type": "gaussian", "center": 520, "fwhm": 40}, "reflectance": 0.7, "c": 0.6, "Q": 0.8}},
    "masked_metal": {"type": "mask", "opacity": 0.3, "material": {"type": "rough_conductor", "reflectance": 0.8, "alpha": 0.3}},
    "blend_jung_metal": {"type": "blend", "weight": 0.4, "materials": [{"type": "jung_fluorescent",
                         "absorption": {"type": "gaussian", "center": 420, "fwhm": 60, "peak": 0.9},
                         "emission": {"type": "gaussian", "center": 520, "fwhm": 40}, "reflectance": 0.7, "c": 0.6, "Q": 0.8},
                         {"type": "rough_conductor", "reflectance": 0.8, "alpha": 0.3}]},
    "blend_mirror_glass": {"type": "blend", "weight": 1, "weight_texture": {"type": "checkerboard", "color0": 0.7, "color1": 0.1},
                           "materials": [{"type": "mirror", "reflectance": 0.9}, {"type": "rough_dielectric", "ior": "BK7", "alpha": 0.3}]},
    "zhdanov_matte": {"type": "zhdanov", "gloss": 0, "passive": 0.4,
                      "excitation": {"type": "gaussian", "center": 400, "fwhm": 50, "peak": 0.3},
                      "emission": {"type": "gaussian", "center": 560, "fwhm": 60}}
  },
  "shapes": [{"name": "s", "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "lambertian"}],
  "lights": [{"type": "distant", "direction": [0, -1, 0], "irradiance": "D65"}]
})";

// Materials whose direction sampling depends on λ (the flag must be set and true).
const std::set<std::string> kWavelengthDependent = {"rough_glass", "coated", "zhdanov", "masked_jung", "blend_mirror_glass"};

struct Subject {
  std::string name;
  const Material* material;
  Bsdf bsdf;
  WavelengthRange range;
};

// Every material of the four scenes (textured_materials.json textures every kind); textured ones
// at a 5×5 grid of texture coordinates.
const std::vector<Subject>& subjects() {
  static const std::unique_ptr<Scene> analytic = loadSceneFromString(kAnalytic, "analytic.json");
  static const std::unique_ptr<Scene> postit = loadScene(test::sourcePath("scenes/postit_uv.json"));
  static const std::unique_ptr<Scene> ink = loadScene(test::sourcePath("scenes/fluorescent_ink.json"));
  static const std::unique_ptr<Scene> textured = loadScene(test::sourcePath("scenes/textured_materials.json"));
  static const std::vector<Subject> all = [] {
    std::vector<Subject> v;
    const Frame world{Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    const float lambda = 550.0f;
    for (const Scene* s : {analytic.get(), postit.get(), ink.get(), textured.get()})
      for (size_t m = 0; m < s->materials.size(); ++m) {
        const Material& mat = *s->materials[m];
        const int n = mat.textured() ? 5 : 1;
        for (int i = 0; i < n * n; ++i) {
          const Vec2 uv((float(i % n) + 0.5f) / float(n), (float(i / n) + 0.5f) / float(n));
          v.push_back({s->materialNames[m], &mat, mat.bsdf(HitContext{uv, world, world, {&lambda, 1}}), s->range});
        }
      }
    return v;
  }();
  return all;
}

TEST(BsdfInterface, EveryMaterialTypeIsCovered) {
  std::set<std::string> types;
  for (const Subject& s : subjects()) types.insert(s.material->describe().substr(0, s.material->describe().find(' ')));
  for (const char* t : {"lambertian", "mirror", "dielectric", "thin_dielectric", "rough_conductor", "rough_dielectric", "jung_fluorescent",
                        "coated_fluorescent", "zhdanov", "measured_reradiation", "mask(jung_fluorescent)",
                        "blend(jung_fluorescent,"})
    EXPECT_TRUE(types.count(t)) << t;
  std::set<std::string> textured;
  for (const Subject& s : subjects())
    if (s.material->textured()) textured.insert(s.material->describe().substr(0, s.material->describe().find(' ')));
  for (const char* t : {"lambertian", "mirror", "rough_conductor", "rough_dielectric", "jung_fluorescent",
                        "coated_fluorescent", "zhdanov", "measured_reradiation"})
    EXPECT_TRUE(textured.count(t)) << t << " textured";
}

// P_F(λ) = 1 − p_elastic(λ) wherever anything scatters, and sampleSpectral over a stratified grid
// of u picks the fluorescent lobe with exactly that frequency (up to the grid's 1/N).
TEST(BsdfInterface, FluorescentEventProbabilityIsOneMinusTheElasticDensity) {
  constexpr int kN = 2000;
  for (const Subject& s : subjects())
    for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance})
      for (float l = s.range.min + 5.0f; l < s.range.max; l += 10.0f) {
        const float pF = s.bsdf.fluorescenceProbability(mode, l);
        const float pE = s.bsdf.spectralPdf(mode, l, l, SpectralLobe::Elastic);
        int fluorescent = 0, elastic = 0;
        for (int k = 0; k < kN; ++k) {
          const float u = (float(k) + 0.5f) / kN;
          const SpectralChoice c = s.bsdf.sampleSpectral(mode, l, u);
          if (!(c.pdf > 0.0f)) continue;
          // The fluorescent lobe exactly for u below P (what hero wavelengths rely on).
          if (std::abs(u - pF) > 1e-5f) EXPECT_EQ(c.lobe == SpectralLobe::Fluorescent, u < pF) << s.name << " u " << u;
          ++(c.lobe == SpectralLobe::Fluorescent ? fluorescent : elastic);
        }
        const std::string where = s.name + " " + toString(mode) + " at " + std::to_string(l) + " nm";
        if (fluorescent + elastic == 0) {  // nothing scatters
          EXPECT_EQ(pF, 0.0f) << where;
          EXPECT_EQ(pE, 0.0f) << where;
          continue;
        }
        EXPECT_NEAR(pF, 1.0f - pE, 1e-5f) << where;
        EXPECT_NEAR(double(fluorescent) / kN, pF, 2.0 / kN) << where;
        EXPECT_NEAR(double(elastic) / kN, pE, 2.0 / kN) << where;
        if (!s.bsdf.has(BsdfFlags::Fluorescent)) EXPECT_EQ(pF, 0.0f) << where;
      }
}

// Calls fn(mode, wKnown, wSampled) for 200 random direction pairs per transport mode, the known
// direction above the surface.
template <class Fn>
void forRandomDirections(Rng& rng, Fn fn) {
  for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance})
    for (int k = 0; k < 200; ++k) {
      Vec3 wKnown = test::randomDirection(rng);
      wKnown.z = std::abs(wKnown.z);
      fn(mode, wKnown, test::randomDirection(rng));
    }
}

TEST(BsdfInterface, FlagsTellTheTruth) {
  Rng rng(17, 0);
  for (const Subject& s : subjects()) {
    EXPECT_EQ(uint8_t(s.bsdf.flags()) & ~uint8_t(s.material->flags()), 0) << s.name << ": not in the material's flags";
    if (s.bsdf.has(BsdfFlags::DeltaDirection)) continue;
    bool differs = false;
    forRandomDirections(rng, [&](TransportMode mode, const Vec3& wKnown, const Vec3& wSampled) {
      const float base = s.bsdf.directionPdf({mode, SpectralLobe::Elastic, 550.0f, 550.0f}, wKnown, wSampled);
      for (float l : {420.0f, 480.0f, 620.0f, 700.0f}) {
        const float p = s.bsdf.directionPdf({mode, SpectralLobe::Elastic, l, l}, wKnown, wSampled);
        if (std::abs(p - base) > 1e-5f * std::max(p, base)) differs = true;
      }
    });
    if (!s.bsdf.has(BsdfFlags::WavelengthDependentDirection))
      EXPECT_FALSE(differs) << s.name << ": its direction density depends on λ but it is not flagged";
    if (kWavelengthDependent.count(s.name))
      EXPECT_TRUE(differs && s.bsdf.has(BsdfFlags::WavelengthDependentDirection)) << s.name;
  }
}

// The contract wavelength lanes rely on (docs/wavelength-sampling.md): a fluorescent lobe's
// direction density is the same for every pair of wavelengths, so one direction serves every lane.
TEST(BsdfInterface, FluorescentDirectionDensityIgnoresTheWavelengths) {
  Rng rng(23, 0);
  for (const Subject& s : subjects()) {
    if (!s.bsdf.has(BsdfFlags::Fluorescent)) continue;
    int compared = 0;
    forRandomDirections(rng, [&](TransportMode mode, const Vec3& wKnown, const Vec3& wSampled) {
      const float base = s.bsdf.directionPdf({mode, SpectralLobe::Fluorescent, 400.0f, 550.0f}, wKnown, wSampled);
      for (const auto& [li, lo] : {std::pair{380.0f, 700.0f}, {450.0f, 460.0f}, {520.0f, 640.0f}}) {
        const float p = s.bsdf.directionPdf({mode, SpectralLobe::Fluorescent, li, lo}, wKnown, wSampled);
        EXPECT_NEAR(p, base, 1e-6f * std::max(p, base)) << s.name << " " << toString(mode);
        compared += base > 0.0f;
      }
    });
    EXPECT_GT(compared, 100) << s.name << ": the test saw no positive density";
  }
}

// FactorisedFluorescence (Kasha's rule) is what lanes through fluorescence rely on to draw every
// fresh lane from one density: the fluorescent lobe's spectral density divided by its probability
// must not depend on the known wavelength. Jung's and Zhdanov's models carry it; a measured
// reradiation matrix, whose excitation spectrum may change with the emission, does not.
TEST(BsdfInterface, FactorisedFluorescenceHasOneExcitationDensity) {
  int flagged = 0;
  for (const Subject& s : subjects()) {
    if (!s.bsdf.has(BsdfFlags::FactorisedFluorescence)) continue;
    EXPECT_TRUE(s.bsdf.has(BsdfFlags::Fluorescent)) << s.name;
    ++flagged;
    for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
      int compared = 0;
      for (float other = s.range.min; other <= s.range.max; other += 7.0f) {
        float first = -1.0f;
        for (float known = s.range.min + 3.0f; known <= s.range.max; known += 29.0f) {
          const float pFl = s.bsdf.fluorescenceProbability(mode, known);
          if (!(pFl > 0.0f)) continue;
          const float q = s.bsdf.spectralPdf(mode, known, other, SpectralLobe::Fluorescent) / pFl;
          if (first < 0.0f) first = q;
          EXPECT_NEAR(q, first, 1e-5f * std::max(q, first)) << s.name << " " << toString(mode) << " at " << other;
          compared += q > 0.0f;
        }
      }
      EXPECT_GT(compared, 10) << s.name << " " << toString(mode) << ": the test saw no positive density";
    }
  }
  EXPECT_GT(flagged, 3) << "jung, zhdanov and their textured forms carry the flag";
  for (const Subject& s : subjects())
    if (s.material->describe().rfind("measured_reradiation", 0) == 0)
      EXPECT_FALSE(s.bsdf.has(BsdfFlags::FactorisedFluorescence)) << s.name << ": a measured matrix need not factorise";
}

// Wherever the fluorescent lobe is non-zero, the fluorophore absorbs at λ_i and re-emits at λ_o.
TEST(BsdfInterface, FluorophoreSpectraCoverTheFluorescentLobe) {
  const Vec3 wi = glm::normalize(Vec3(0.3f, 0.1f, 0.9f)), wo = glm::normalize(Vec3(-0.2f, 0.4f, 0.8f));
  for (const Subject& s : subjects()) {
    const std::optional<FluorophoreSpectra> f = s.material->fluorophore();
    ASSERT_EQ(f.has_value(), has(s.material->flags(), BsdfFlags::Fluorescent)) << s.name;
    if (!s.bsdf.has(BsdfFlags::Fluorescent)) continue;
    int nonZero = 0;
    for (float li = s.range.min + 2.5f; li < s.range.max; li += 5.0f)
      for (float lo = s.range.min + 2.5f; lo < s.range.max; lo += 5.0f) {
        if (!(s.bsdf.eval({TransportMode::Radiance, SpectralLobe::Fluorescent, li, lo}, wi, wo) > 0.0f)) continue;
        ++nonZero;
        EXPECT_GT(f->absorbed(li), 0.0f) << s.name << " absorbs at " << li << " nm";
        EXPECT_GT(f->reemitted(lo), 0.0f) << s.name << " re-emits at " << lo << " nm";
      }
    EXPECT_GT(nonZero, 0) << s.name;
  }
}

}  // namespace
}  // namespace kasha
