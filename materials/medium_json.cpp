#include "materials/medium_json.h"

#include <cmath>
#include <stdexcept>

#include "core/error.h"
#include "core/grid_density.h"
#include "core/json_fields.h"
#include "core/volume_grid.h"

namespace kasha {
namespace {

Spectrum spectrumOr(JsonFields& f, const std::string& key, const SpectrumContext& ctx, float fallback) {
  return f.has(key) ? parseSpectrum(f.get(key), ctx, f.path(key)) : Spectrum::constant(fallback);
}

// Centimetres per scene unit.
float centimetresPer(JsonFields& f) {
  const std::string unit = f.string("length_unit", "");
  if (unit == "m") return 100.0f;
  if (unit == "cm") return 1.0f;
  if (unit == "mm") return 0.1f;
  if (unit == "um") return 1e-4f;
  if (unit.empty()) f.fail("length_unit", "is needed with molar_absorption (the scene's unit: m, cm, mm or um)");
  f.fail("length_unit", "'" + unit + "' is not a length unit (m, cm, mm, um)");
}

Fluorophore fluorophore(JsonFields& medium, const nlohmann::json& v, const SpectrumContext& ctx, const std::string& ptr) {
  JsonFields f(v, medium.file(), ptr);
  Fluorophore fl;
  if (f.has("sigma_f") == f.has("molar_absorption"))
    f.fail("sigma_f", "give either sigma_f or molar_absorption with concentration");
  if (f.has("sigma_f")) {
    fl.absorption = parseSpectrum(f.get("sigma_f"), ctx, f.path("sigma_f"));
  } else {
    const Spectrum epsilon = parseSpectrum(f.get("molar_absorption"), ctx, f.path("molar_absorption"));
    const float c = f.number("concentration");
    if (!(c >= 0.0f && std::isfinite(c))) f.fail("concentration", "must be a finite, non-negative molarity (mol/L)");
    fl.absorption = epsilon.scaled(std::log(10.0f) * c * centimetresPer(medium));  // Beer–Lambert, decadic
  }
  fl.emission = parseSpectrum(f.get("emission"), ctx, f.path("emission"));
  fl.yield = f.number("yield");
  f.finish();
  return fl;
}

// "density" of a heterogeneous medium: {"file": "x.vol", "transform": <to_world, optional>,
// "use_grid_bbox": false} (core/grid_density.h); the grid must have one channel.
std::shared_ptr<const DensityField> densityGrid(JsonFields& f, const SpectrumContext& ctx) {
  JsonFields density(f.get("density"), ctx.file, f.path("density"));
  const std::string rel = density.string("file");
  const std::string path = ctx.resolve(rel);
  const glm::mat4 toWorld = density.has("transform") ? density.affine("transform") : glm::mat4(1.0f);
  const bool useGridBox = density.boolean("use_grid_bbox", false);
  density.finish();
  VolumeGrid grid = [&] {
    try {
      return VolumeGrid::read(path, ctx.memoryLimit);
    } catch (const InputError& e) {
      throw InputError(ctx.file, density.path("file"), e.what());
    }
  }();
  if (grid.channels() != 1) density.fail("file", "a density grid has 1 channel, '" + rel + "' has " + std::to_string(grid.channels()));
  return std::make_shared<GridDensity>(std::move(grid), toWorld, useGridBox);
}

}  // namespace

std::unique_ptr<Medium> parseMedium(const std::string& name, const nlohmann::json& v, const SpectrumContext& ctx,
                                    const std::string& pointer, WavelengthRange range) {
  JsonFields f(v, ctx.file, pointer);
  const std::string type = f.string("type");
  if (type != "homogeneous" && type != "heterogeneous")
    f.fail("type", "'" + type + "' is not a medium type (homogeneous, heterogeneous)");
  std::shared_ptr<const DensityField> density;
  if (type == "heterogeneous") {
    density = densityGrid(f, ctx);
    // Camera paths' source-seeking free flights (media.md eq. 6b) need a homogeneous medium.
    if (f.has("fluorophores")) f.fail("fluorophores", "a heterogeneous medium cannot fluoresce yet (media.md §4)");
  }
  MediumParams p;
  p.absorption = spectrumOr(f, "sigma_a", ctx, 0.0f);
  p.scattering = spectrumOr(f, "sigma_s", ctx, 0.0f);
  p.g = f.number("g", 0.0f);
  if (f.has("fluorophores")) {
    const nlohmann::json& list = f.get("fluorophores");
    if (!list.is_array()) f.fail("fluorophores", "expected an array of fluorophores");
    for (size_t k = 0; k < list.size(); ++k)
      p.fluorophores.push_back(fluorophore(f, list[k], ctx, f.path("fluorophores") + "/" + std::to_string(k)));
  }
  if (f.has("length_unit")) centimetresPer(f);  // a misspelt unit is an error even where unused
  f.finish();
  const std::string problem = checkMediumParams(p, range);
  if (!problem.empty()) {
    // "field: reason", the field possibly "fluorophores[k].x": as a JSON pointer below the medium.
    const size_t colon = problem.find(": ");
    std::string field = problem.substr(0, colon);
    if (field.starts_with("fluorophores[")) {
      const size_t close = field.find(']');
      const std::string k = field.substr(13, close - 13), key = field.substr(close + 2);
      const bool molar = key == "sigma_f" && v["fluorophores"][std::stoul(k)].contains("molar_absorption");
      field = "fluorophores/" + k + "/" + (molar ? "molar_absorption" : key);
    }
    throw InputError(ctx.file, pointer + "/" + field, problem.substr(colon + 2));
  }
  return std::make_unique<Medium>(name, std::move(p), range, std::move(density));
}

}  // namespace kasha
