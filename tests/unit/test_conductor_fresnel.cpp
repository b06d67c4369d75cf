// Conductors with a complex index (materials/conductor_fresnel.h, core/conductor_index.h): the
// exact Fresnel reflectance against complex arithmetic written out here, the measured metals
// against the reflectances the data's curator computed (../shared/data/README.md, copied into
// scenes/spectra/README.md), and the scene formats that name them.
#include <gtest/gtest.h>

#include <complex>
#include <filesystem>
#include <set>

#include "core/conductor_index.h"
#include "core/error.h"
#include "materials/fresnel.h"
#include "materials/material_json.h"
#include "materials/mirror.h"
#include "materials/rough_conductor.h"
#include "scene/mitsuba/mitsuba_scene.h"
#include "tests/expect_contains.h"

namespace kasha {
namespace {

const WavelengthRange kRange{360.0f, 830.0f};

// |r_s|² and |r_p|² of the interface from air into n = η + i·k (Born & Wolf §14.2), by complex
// arithmetic: cos θ_t·n = sqrt(n² − sin²θ).
double complexFresnel(double cosI, double eta, double k) {
  const std::complex<double> n(eta, k);
  const double sin2 = 1.0 - cosI * cosI;
  const std::complex<double> nCosT = std::sqrt(n * n - sin2);
  const std::complex<double> rs = (cosI - nCosT) / (cosI + nCosT);
  const std::complex<double> rp = (n * n * cosI - nCosT) / (n * n * cosI + nCosT);
  return 0.5 * (std::norm(rs) + std::norm(rp));
}

TEST(ConductorFresnel, MatchesComplexArithmetic) {
  for (const auto [eta, k] : {std::pair{0.2f, 3.6f}, {1.1f, 6.9f}, {0.05f, 4.2f}, {2.9f, 3.1f}, {1.5f, 0.0f}})
    for (const float c : {1.0f, 0.9f, 0.5f, 0.2f, 0.05f, 0.0f})
      EXPECT_NEAR(fresnelConductor(c, eta, k), complexFresnel(c, eta, k), 2e-5) << eta << " + " << k << "i at cos " << c;
}

TEST(ConductorFresnel, WithoutAbsorptionIsTheDielectrics) {
  for (const float c : {1.0f, 0.7f, 0.3f, 0.01f}) EXPECT_NEAR(fresnelConductor(c, 1.5f, 0.0f), fresnelDielectric(c, 1.5f), 1e-6);
}

TEST(NamedConductors, EveryTableLoadsAndEveryFileIsNamed) {
  std::set<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(std::string(KASHA_SOURCE_DIR) + "/scenes/spectra/conductors"))
    files.insert(e.path().stem().string());
  const std::vector<std::string> names = conductorNames();
  EXPECT_EQ(files, std::set<std::string>(names.begin(), names.end()));
  for (const std::string& n : names) {
    const std::optional<ComplexIndex> index = namedConductor(n);
    ASSERT_TRUE(index) << n;
    for (float l = 300.0f; l <= 830.0f; l += 5.0f) {
      EXPECT_GT(index->eta(l), 0.0f) << n << " at " << l;
      EXPECT_GT(index->k(l), 0.0f) << n << " at " << l;
    }
  }
  EXPECT_FALSE(namedConductor("a-C"));
  EXPECT_FALSE(namedConductor("au"));
}

TEST(NamedConductors, NormalIncidenceReflectanceAsTheDataNotesGiveIt) {
  // ((η−1)² + k²)/((η+1)² + k²) at 450/550/650 nm, as listed with the data.
  const std::map<std::string, std::array<double, 3>> expected = {{"Ag", {0.980, 0.983, 0.990}},
                                                                 {"Al", {0.922, 0.915, 0.906}},
                                                                 {"Au", {0.408, 0.792, 0.957}},
                                                                 {"Cu", {0.538, 0.624, 0.935}}};
  for (const auto& [metal, f0] : expected) {
    const ComplexIndex index = *namedConductor(metal);
    for (int i = 0; i < 3; ++i) {
      const float l = 450.0f + 100.0f * float(i);
      EXPECT_NEAR(fresnelConductor(1.0f, index.eta(l), index.k(l)), f0[size_t(i)], 6e-4) << metal << " at " << l;
    }
  }
}

TEST(NamedConductors, MaterialsReflectTheMetalsFresnelTimesTheirReflectance) {
  const SpectrumContext ctx{"scene.json", "."};
  const std::unique_ptr<Material> goldMaterial =
      parseMaterial({{"type", "mirror"}, {"eta", "Au"}}, ctx, "/materials/gold", kRange);
  const std::unique_ptr<Material> halfMaterial =
      parseMaterial({{"type", "mirror"}, {"eta", "Au"}, {"reflectance", 0.5}}, ctx, "/materials/half", kRange);
  const Mirror& gold = dynamic_cast<const Mirror&>(*goldMaterial);
  const Mirror& half = dynamic_cast<const Mirror&>(*halfMaterial);
  const ComplexIndex au = *namedConductor("Au");
  for (const float c : {1.0f, 0.6f, 0.1f}) {
    const Vec3 w(std::sqrt(1.0f - c * c), 0.0f, c), mirrored(-w.x, 0.0f, c);
    for (const float l : {450.0f, 550.0f, 650.0f}) {
      const double F = complexFresnel(c, au.eta(l), au.k(l));
      const std::optional<ScatterSample> s = gold.sample(TransportMode::Radiance, w, l, Vec3(0.5f));
      ASSERT_TRUE(s);
      EXPECT_NEAR(s->f * c / s->pdf, F, 1e-4) << "cos " << c << " at " << l;
      EXPECT_NEAR(half.eval({TransportMode::Radiance, SpectralLobe::Elastic, l, l}, mirrored, w) * c, 0.5 * F, 1e-4);
    }
  }
  // A rough conductor's F at the microfacet normal, against the same microfacet term with F = 1.
  const RoughConductor rough(Spectrum::constant(1.0f), 0.3f, 0.3f, {}, std::make_shared<const ComplexIndex>(au));
  const Vec3 wi = glm::normalize(Vec3(0.3f, 0.1f, 0.8f)), wo = glm::normalize(Vec3(-0.5f, 0.2f, 0.7f));
  const RoughConductor schlickOne(Spectrum::constant(1.0f), 0.3f, 0.3f);  // F = 1: the bare microfacet term
  const Vec3 h = glm::normalize(wi + wo);
  const float l = 520.0f;
  EXPECT_NEAR(rough.eval({TransportMode::Radiance, SpectralLobe::Elastic, l, l}, wi, wo),
              complexFresnel(glm::dot(wi, h), au.eta(l), au.k(l)) *
                  schlickOne.eval({TransportMode::Radiance, SpectralLobe::Elastic, l, l}, wi, wo),
              1e-4);
}

TEST(NamedConductors, BadIndicesAreOneLineErrors) {
  const SpectrumContext ctx{"scene.json", "."};
  const auto error = [&](const nlohmann::json& j) {
    try {
      parseMaterial(j, ctx, "/materials/m", kRange);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_CONTAINS(error({{"type", "mirror"}, {"eta", "Unobtainium"}}),
                             "scene.json: /materials/m/eta: no measured index for the metal 'Unobtainium' (Ag, Al, Au");
  EXPECT_CONTAINS(error({{"type", "rough_conductor"}, {"alpha", 0.1}, {"eta", 0.2}}),
                             "/materials/m/eta: a spectrum for eta needs \"k\" as well");
  EXPECT_CONTAINS(error({{"type", "mirror"}, {"k", 3.0}}), "/materials/m/k: needs \"eta\" as well");
  EXPECT_CONTAINS(error({{"type", "mirror"}, {"eta", -1.0}, {"k", 3.0}}), "/materials/m/eta: spectrum value must not be negative");
}

TEST(NamedConductors, MitsubasMaterialNames) {
  const std::string head = R"(<scene version="3.0.0"><sensor type="perspective"><float name="fov" value="40"/></sensor>)";
  const auto translated = [&](const std::string& bsdf) {
    return mitsuba::translateMitsubaScene(head + bsdf + R"(<shape type="sphere"><ref id="m"/></shape></scene>)",
                                          "/tmp/conductors.xml", {});
  };
  const mitsuba::Translation gold = translated(R"(<bsdf type="conductor" id="m"><string name="material" value="Au"/></bsdf>)");
  EXPECT_EQ(gold.scene["materials"]["m"], nlohmann::json({{"type", "mirror"}, {"reflectance", 1.0}, {"eta", "Au"}, {"one_sided", true}}));
  const mitsuba::Translation palik =
      translated(R"(<bsdf type="roughconductor" id="m"><string name="material" value="Cu_palik"/></bsdf>)");
  EXPECT_EQ(palik.scene["materials"]["m"]["eta"], "Cu");
  bool noted = false;
  for (const std::string& n : palik.notes) noted |= n.find("'Cu_palik' is kasha's measured 'Cu'") != std::string::npos;
  EXPECT_TRUE(noted);
  try {
    translated(R"(<bsdf type="conductor" id="m"><string name="material" value="a-C"/></bsdf>)");
    ADD_FAILURE() << "a-C accepted";
  } catch (const InputError& e) {
    EXPECT_CONTAINS(e.what(), "/tmp/conductors.xml:1: bsdf 'conductor': no measured index for the conductor 'a-C' in kasha");
  }
}

}  // namespace
}  // namespace kasha
