// The measured reradiation-matrix material (materials/measured_reradiation.h) and the bispectral
// file readers (core/bispectral_data.h, core/bispectral_exr.h): χ² sampling in both transport
// modes between and on the measured wavelengths, sample()/pdf() consistency, normalisation of the
// spectral densities, noise clamping, the energy check, the Post-it measurements, reading errors,
// and a CSV → OpenEXR → material round trip.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <tuple>
#include <vector>

#include "core/bispectral_exr.h"
#include "core/error.h"
#include "materials/material_json.h"
#include "materials/measured_reradiation.h"
#include "tests/material_chi2.h"
#include "tests/material_support.h"
#include "tests/support.h"

namespace kasha {
namespace {

using test::close;

const WavelengthRange kRange{360.0f, 830.0f};

// Inputs 350–700 nm and outputs 400–750 nm, both every 25 nm: a diagonal reflectance and a
// Stokes-shifted band whose shape depends on the input (not factorisable), plus noise to clamp.
BispectralData synthetic() {
  BispectralData d;
  d.source = "synthetic";
  for (float l = 350.0f; l <= 700.0f; l += 25.0f) d.in.push_back(l);
  for (float l = 400.0f; l <= 750.0f; l += 25.0f) d.out.push_back(l);
  d.value.assign(d.in.size() * d.out.size(), 0.0f);
  for (size_t o = 0; o < d.out.size(); ++o)
    for (size_t i = 0; i < d.in.size(); ++i) {
      const float li = d.in[i], lo = d.out[o];
      if (lo == li) d.at(o, i) = 0.3f + 0.5f * (li - 400.0f) / 350.0f;
      else if (lo > li && li < 500.0f) d.at(o, i) = 0.04f * std::exp(-std::pow((lo - li - 120.0f) / 60.0f, 2.0f));
      else if (lo < li) d.at(o, i) = (o + i) % 2 ? -0.001f : 0.0015f;  // anti-Stokes noise
    }
  return d;
}

TEST(MeasuredReradiation, NoiseIsClampedAndBandsBecomeDensities) {
  const BispectralData d = synthetic();
  const MeasuredReradiation m(d, {}, kRange);
  EXPECT_TRUE(has(m.flags(), BsdfFlags::Fluorescent));
  // Anti-Stokes and negative values are gone; at the knots F = value / 25 nm.
  EXPECT_EQ(m.F(400.0f, 450.0f), 0.0f);
  EXPECT_EQ(m.F(425.0f, 700.0f), 0.0f);
  EXPECT_TRUE(close(m.F(550.0f, 425.0f), d.at(6, 3) / 25.0f, 1e-6));
  EXPECT_TRUE(close(m.diagonal(450.0f), d.at(2, 4), 1e-6));
  // Between knots: bilinear.
  const float f00 = m.F(550.0f, 400.0f), f01 = m.F(575.0f, 400.0f), f10 = m.F(550.0f, 425.0f),
              f11 = m.F(575.0f, 425.0f);
  EXPECT_TRUE(close(m.F(560.0f, 410.0f), 0.6 * 0.6 * f00 + 0.6 * 0.4 * f01 + 0.4 * 0.6 * f10 + 0.4 * 0.4 * f11, 1e-5));
  // A floor above the band's values removes the fluorescence.
  EXPECT_FALSE(has(MeasuredReradiation(d, {0.05f, false}, kRange).flags(), BsdfFlags::Fluorescent));
}

TEST(MeasuredReradiation, Chi2BothModes) {
  const MeasuredReradiation m(synthetic(), {}, kRange);
  uint64_t seed = 3;
  for (const TransportMode mode : {TransportMode::Radiance, TransportMode::Importance})
    for (const float l : {425.0f, 437.0f, 480.0f, 590.0f, 612.5f}) {
      SCOPED_TRACE(std::string(toString(mode)) + " λ = " + std::to_string(l));
      test::Chi2Config cfg;
      cfg.nCos = 4;
      cfg.nPhi = 4;
      cfg.binNm = 5.0f;
      cfg.subNm = 5;
      cfg.samples = 100000;
      const test::Chi2Result r = test::jointChi2(m, mode, glm::normalize(Vec3(0.2f, 0.1f, 0.9f)), l, seed++, cfg);
      EXPECT_GT(r.p, 1e-3);
      EXPECT_EQ(r.failed, 0);
    }
}

TEST(MeasuredReradiation, SampleMatchesPdfAndDensitiesIntegrateToOne) {
  const MeasuredReradiation m(synthetic(), {}, kRange);
  Rng rng(8);
  for (int k = 0; k < 20000; ++k) {
    const TransportMode mode = (k & 1) ? TransportMode::Radiance : TransportMode::Importance;
    const Vec3 w = test::randomDirection(rng);
    const float l = 360.0f + rng.uniform() * 470.0f;
    const auto s = m.sample(mode, w, l, Vec3(rng.uniform(), rng.uniform(), rng.uniform()));
    if (!s) continue;
    const test::Event ev = test::physical(mode, w, l, s->w, s->lambda);
    const ScatterDensity d = m.pdf({mode, s->lobe, ev.lambdaIn, ev.lambdaOut}, ev.wi, ev.wo);
    EXPECT_TRUE(close(s->pdf, d.pdf, 1e-4));
    EXPECT_TRUE(close(s->pdfRev, d.pdfRev, 1e-4, 1e-30));
    EXPECT_TRUE(close(s->f, m.eval({mode, s->lobe, ev.lambdaIn, ev.lambdaOut}, ev.wi, ev.wo), 1e-6));
    // The sample weight is the albedo of the known side: d + A (light) or d + B (camera).
    const float albedo = m.diagonal(l) + (mode == TransportMode::Importance ? m.A(l) : m.B(l));
    EXPECT_TRUE(close(s->f * std::abs(s->w.z) / s->pdf, albedo, 1e-3)) << toString(mode) << " λ = " << l;
  }
  // Spectral stage: elastic probability + ∫ fluorescent density = 1 wherever anything scatters.
  for (const TransportMode mode : {TransportMode::Radiance, TransportMode::Importance})
    for (const float l : {350.0f, 400.0f, 412.5f, 450.0f, 530.0f, 700.0f, 740.0f}) {
      double total = m.spectralPdf(mode, l, l, SpectralLobe::Elastic);
      for (int k = 0; k < 47000; ++k)
        total += 0.01 * m.spectralPdf(mode, l, float(360.0 + (k + 0.5) * 0.01), SpectralLobe::Fluorescent);
      const float albedo = m.diagonal(l) + (mode == TransportMode::Importance ? m.A(l) : m.B(l));
      EXPECT_TRUE(close(total, albedo > 0.0f ? 1.0 : 0.0, 1e-4)) << toString(mode) << " λ = " << l;
    }
}

// f is reciprocal in directions, not in wavelengths (fluorescence only shifts to longer ones).
TEST(MeasuredReradiation, DirectionallyReciprocalNotSpectrally) {
  const MeasuredReradiation m(synthetic(), {}, kRange);
  Rng rng(4);
  for (int k = 0; k < 1000; ++k) {
    const Vec3 a = test::randomDirection(rng), b = test::randomDirection(rng);
    const float li = 350.0f + 150.0f * rng.uniform(), lo = 500.0f + 200.0f * rng.uniform();
    for (const SpectralLobe lobe : {SpectralLobe::Elastic, SpectralLobe::Fluorescent})
      EXPECT_EQ(m.eval({TransportMode::Radiance, lobe, li, lo}, a, b),
                m.eval({TransportMode::Importance, lobe, li, lo}, b, a));
  }
  const Vec3 n(0, 0, 1);
  EXPECT_GT(m.eval({TransportMode::Radiance, SpectralLobe::Fluorescent, 425.0f, 550.0f}, n, n), 0.0f);
  EXPECT_EQ(m.eval({TransportMode::Radiance, SpectralLobe::Fluorescent, 550.0f, 425.0f}, n, n), 0.0f);
}

TEST(MeasuredReradiation, EnergyAboveOneIsAnError) {
  BispectralData d = synthetic();
  d.at(2, 4) = 0.99f;  // diagonal at 450 nm plus its fluorescence exceeds 1
  try {
    MeasuredReradiation m(d, {}, kRange);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("synthetic"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("ex_450"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(MeasuredReradiation(d, {0.002f, true}, kRange));
}

TEST(MeasuredReradiation, PostItMeasurementsLoadWithinEnergy) {
  for (const char* name : {"pink", "yellow"}) {
    const BispectralData d =
        readBispectralCsv(test::sourcePath("scenes/spectra/bispectral_" + std::string(name) + "_postit_labsphere.csv"));
    EXPECT_EQ(d.in.size(), 49u);
    EXPECT_EQ(d.out.size(), 41u);
    const MeasuredReradiation m(d, {}, WavelengthRange{300.0f, 830.0f});
    EXPECT_TRUE(has(m.flags(), BsdfFlags::Fluorescent)) << name;
    for (float l = 300.0f; l <= 780.0f; l += 10.0f) EXPECT_LE(m.diagonal(l) + m.A(l), 1.0f + kEnergyTolerance);
  }
}

// ---------------------------------------------------------------------------------------------
// Files

std::string writeTemp(const std::string& name, const std::string& text) {
  const std::string path = (std::filesystem::temp_directory_path() / ("kasha_bispectral_" + name)).string();
  std::ofstream(path) << text;
  return path;
}

void expectCsvError(const std::string& name, const std::string& text, const std::string& reason) {
  const std::string path = writeTemp(name, text);
  try {
    readBispectralCsv(path);
    FAIL() << name << ": no error";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    EXPECT_NE(msg.find(reason), std::string::npos) << msg;
  }
}

TEST(BispectralFiles, CsvErrorsNameFileAndReason) {
  expectCsvError("missing.csv", "", "");
  std::filesystem::remove(std::filesystem::temp_directory_path() / "kasha_bispectral_missing.csv");
  expectCsvError("ragged.csv", "out,ex_400,ex_410\n400,0.5,0\n410,0.1\n", "fields");
  expectCsvError("rows.csv", "out,ex_400,ex_410\n410,0.5,0\n400,0.1,0.2\n", "strictly increasing");
  expectCsvError("cols.csv", "out,ex_410,ex_400\n400,0.5,0\n410,0.1,0.2\n", "ex_400: input wavelengths must be");
  expectCsvError("header.csv", "out,ex_400,em_410\n400,0.5,0\n410,0.1,0.2\n", "em_410: header cell");
  expectCsvError("number.csv", "out,ex_400\n400,abc\n", "not a number");
}

TEST(BispectralFiles, SceneMaterialErrorsNameTheField) {
  const auto parse = [](const nlohmann::json& j) {
    SpectrumContext ctx("scene.json", std::filesystem::temp_directory_path().string());
    return parseMaterial(j, ctx, "/materials/m", kRange);
  };
  try {
    parse({{"type", "measured_reradiation"}, {"file", "x.txt"}});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/materials/m/file"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse({{"type", "measured_reradiation"}, {"file", "kasha_no_such_file.csv"}}), InputError);
  EXPECT_THROW(parse({{"type", "measured_reradiation"}, {"file", "kasha_no_such_file.exr"}}), InputError);
  const std::string ok = writeTemp("ok.csv", "out,ex_400,ex_410\n400,0.5,0.1\n410,0.1,0.2\n");
  EXPECT_NO_THROW(parse({{"type", "measured_reradiation"}, {"file", ok}}));
  EXPECT_THROW(parse({{"type", "measured_reradiation"}, {"file", ok}, {"noise_floor", -1}}), InputError);
  EXPECT_THROW(parse({{"type", "measured_reradiation"}, {"file", ok}, {"nois_floor", 0.1}}), InputError);
  // A material in its own file: missing, not JSON, or with a bad field (named inside that file).
  for (const auto& [name, text, expected] :
       std::vector<std::tuple<std::string, std::string, std::string>>{
           {"kasha_no_such_material.json", "", "/materials/m/file"},
           {"kasha_bad_material.json", "{\"type\": ", "malformed JSON"},
           {"kasha_bad_field.json", "{\"type\": \"zhdanov\", \"passive\": 0.5, \"excitation\": 0, \"emission\": 1, "
                                    "\"gloss\": 2}", "gloss"}}) {
    const std::string path = text.empty() ? name : writeTemp(name, text);
    try {
      parse({{"type", "file"}, {"file", path}});
      FAIL() << name;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  }
}

TEST(BispectralFiles, FichetChannelNames) {
  const auto c = parseBispectralChannel("T.550,000000nm");
  ASSERT_TRUE(c);
  EXPECT_FLOAT_EQ(c->lambdaIn, 550.0f);
  EXPECT_FALSE(c->lambdaOut);
  const auto r = parseBispectralChannel("T.0,45um.0,6um");
  ASSERT_TRUE(r && r->lambdaOut);
  EXPECT_FLOAT_EQ(r->lambdaIn, 450.0f);
  EXPECT_FLOAT_EQ(*r->lambdaOut, 600.0f);
  const auto hz = parseBispectralChannel("T.599,584916THz");  // c / 599.584916 THz = 500 nm
  ASSERT_TRUE(hz);
  EXPECT_NEAR(hz->lambdaIn, 500.0f, 1e-3f);
  const auto e = parseBispectralChannel("T.5,5e2nm.6e+2nm");  // exponents
  ASSERT_TRUE(e && e->lambdaOut);
  EXPECT_FLOAT_EQ(e->lambdaIn, 550.0f);
  EXPECT_FLOAT_EQ(*e->lambdaOut, 600.0f);
  for (const char* other : {"R", "S0.550nm", "T.550", "T.nm", "T.550nm.", "T.550xm", "T.550nm.600nm.700nm", "XYZ.X"})
    EXPECT_FALSE(parseBispectralChannel(other)) << other;
}

TEST(BispectralFiles, CsvToExrToMaterialRoundTrip) {
  const BispectralData csv = readBispectralCsv(test::sourcePath("scenes/spectra/bispectral_pink_postit_labsphere.csv"));
  const std::string path = (std::filesystem::temp_directory_path() / "kasha_postit_roundtrip.exr").string();
  writeBispectralExr(path, csv);
  const BispectralData exr = readBispectralExr(path);
  ASSERT_EQ(exr.in, csv.in);
  ASSERT_EQ(exr.out, csv.out);
  for (size_t k = 0; k < csv.value.size(); ++k) EXPECT_EQ(exr.value[k], csv.value[k]) << k;
  const WavelengthRange range{300.0f, 830.0f};
  const MeasuredReradiation a(csv, {}, range), b(exr, {}, range);
  for (float li = 300.0f; li < 780.0f; li += 7.0f)
    for (float lo = 380.0f; lo < 780.0f; lo += 11.0f) EXPECT_EQ(a.F(lo, li), b.F(lo, li));
  // Not an EXR, or an EXR without T.* channels.
  EXPECT_THROW(readBispectralExr(writeTemp("bad.exr", "not an exr")), InputError);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace kasha
