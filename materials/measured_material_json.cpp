#include "materials/measured_material_json.h"

#include "core/bispectral_exr.h"
#include "materials/measured_reradiation.h"
#include "materials/texture_json.h"
#include "materials/zhdanov_bdf.h"

namespace kasha {

std::unique_ptr<Material> parseZhdanov(JsonFields& f, const SpectrumContext& ctx, WavelengthRange range,
                                       bool allowUnphysical) {
  ZhdanovParams p;
  p.gloss = f.number("gloss", 0.0f);
  p.glossExponent = f.number("gloss_exponent", p.glossExponent);
  p.passive = parseSpectrum(f.get("passive"), ctx, f.path("passive"));
  p.excitation = parseSpectrum(f.get("excitation"), ctx, f.path("excitation"));
  p.emission = parseSpectrum(f.get("emission"), ctx, f.path("emission"));
  p.allowUnphysical = allowUnphysical;
  if (const std::string problem = checkZhdanovParams(p, range); !problem.empty()) {
    const size_t colon = problem.find(": ");
    f.fail(problem.substr(0, colon), problem.substr(colon + 2));
  }
  ZhdanovTextures tex{parseScalarTexture(f, "gloss_texture", ctx), parseScalarTexture(f, "gloss_exponent_texture", ctx),
                      parseReflectanceTexture(f, "passive_texture", ctx), parseScalarTexture(f, "excitation_texture", ctx)};
  return std::make_unique<ZhdanovBdf>(std::move(p), range, std::move(tex));
}

std::unique_ptr<Material> parseMeasuredReradiation(JsonFields& f, const SpectrumContext& ctx, WavelengthRange range,
                                                   bool allowUnphysical) {
  const std::string rel = f.string("file");
  const std::string path = ctx.resolve(rel);
  MeasuredReradiationOptions o;
  o.noiseFloor = f.number("noise_floor", o.noiseFloor);
  if (!(o.noiseFloor >= 0.0f)) f.fail("noise_floor", "must be a number ≥ 0");
  o.allowUnphysical = allowUnphysical;
  const auto endsWith = [&](const char* ext) {
    const std::string e(ext);
    return rel.size() >= e.size() && rel.compare(rel.size() - e.size(), e.size(), e) == 0;
  };
  MeasuredTextures tex{parseScalarTexture(f, "reflectance_texture", ctx), parseScalarTexture(f, "reradiation_texture", ctx)};
  try {  // errors in the matrix file name it; the scene's field comes first
    if (endsWith(".csv")) return std::make_unique<MeasuredReradiation>(readBispectralCsv(path), o, range, tex);
    if (endsWith(".exr")) return std::make_unique<MeasuredReradiation>(readBispectralExr(path), o, range, tex);
  } catch (const InputError& e) {
    f.fail("file", e.what());
  }
  f.fail("file", "'" + rel + "': expected a .csv or .exr bispectral matrix");
}

}  // namespace kasha
