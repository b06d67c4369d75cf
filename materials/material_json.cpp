#include "materials/material_json.h"

#include <stdexcept>

#include "core/json_fields.h"
#include "materials/jung_bbrrdf.h"
#include "materials/lambertian.h"

namespace kasha {
namespace {

Spectrum spectrumField(JsonFields& f, const std::string& key, const SpectrumContext& ctx) {
  return parseSpectrum(f.get(key), ctx, f.path(key));
}

// Reflectances above 1 create energy; reject them (issue: physical-parameter violations are errors).
void requireAlbedo(JsonFields& f, const std::string& key, const Spectrum& s, WavelengthRange range) {
  const float hi = s.maxValue(range.min, range.max);
  if (hi > 1.0f + 1e-6f) f.fail(key, "reflectance " + std::to_string(hi) + " exceeds 1 in the wavelength range");
}

}  // namespace

std::unique_ptr<Material> parseMaterial(const nlohmann::json& v, const SpectrumContext& ctx, const std::string& ptr,
                                        WavelengthRange range) {
  JsonFields f(v, ctx.file, ptr);
  const std::string type = f.string("type");
  std::unique_ptr<Material> m;
  if (type == "lambertian") {
    Spectrum r = spectrumField(f, "reflectance", ctx);
    requireAlbedo(f, "reflectance", r, range);
    m = std::make_unique<Lambertian>(std::move(r));
  } else if (type == "jung_fluorescent") {
    JungParams p;
    p.absorption = spectrumField(f, "absorption", ctx);
    p.emission = spectrumField(f, "emission", ctx);
    p.reflectance = spectrumField(f, "reflectance", ctx);
    p.concentration = f.number("c");
    p.energyRatio = f.number("Q");
    const std::string problem = checkJungParams(p, range);
    if (!problem.empty()) {
      const size_t colon = problem.find(": ");
      f.fail(problem.substr(0, colon), problem.substr(colon + 2));
    }
    m = std::make_unique<JungBbrrdf>(std::move(p), range);
  } else {
    f.fail("type", "unknown material type '" + type + "' (lambertian, jung_fluorescent)");
  }
  f.finish();
  return m;
}

}  // namespace kasha
