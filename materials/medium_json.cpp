#include "materials/medium_json.h"

#include <cmath>
#include <stdexcept>

#include "core/error.h"
#include "core/grid_albedo.h"
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

// The grid of `g`, an object {"file": "x.vol", "transform": <to_world, optional>, "use_grid_bbox":
// false} placed as Mitsuba's gridvolume (core/volume_grid.h), whose other keys the caller has read:
// checks that `g` has no others, then reads the file (its errors name g's "file").
struct PlacedGrid {
  VolumeGrid grid;
  glm::mat4 toWorld;
  bool useGridBox;
};
PlacedGrid placedGrid(JsonFields& g, const SpectrumContext& ctx) {
  const std::string path = ctx.resolve(g.string("file"));
  const glm::mat4 toWorld = g.has("transform") ? g.affine("transform") : glm::mat4(1.0f);
  const bool useGridBox = g.boolean("use_grid_bbox", false);
  g.finish();
  try {
    return {VolumeGrid::read(path, ctx.memoryLimit), toWorld, useGridBox};
  } catch (const InputError& e) {
    throw InputError(ctx.file, g.path("file"), e.what());
  }
}

// "density" of a heterogeneous medium (core/grid_density.h): a placed grid of one channel.
std::shared_ptr<const DensityField> densityGrid(JsonFields& f, const SpectrumContext& ctx) {
  JsonFields density(f.get("density"), ctx.file, f.path("density"));
  PlacedGrid g = placedGrid(density, ctx);
  if (g.grid.channels() != 1)
    density.fail("file", "a density grid has 1 channel, '" + density.string("file") + "' has " + std::to_string(g.grid.channels()));
  return std::make_shared<GridDensity>(std::move(g.grid), g.toWorld, g.useGridBox);
}

// "albedo_grid" of a homogeneous medium (core/grid_albedo.h; media.md §7): a placed grid of
// linear sRGB (3 channels) or grey (1) values in [0, 1], and "wrap_mode": "clamp" (default),
// "repeat" or "mirror".
std::shared_ptr<const AlbedoField> albedoGrid(JsonFields& f, const SpectrumContext& ctx) {
  JsonFields albedo(f.get("albedo_grid"), ctx.file, f.path("albedo_grid"));
  const std::string wrapName = albedo.string("wrap_mode", "clamp");
  const std::optional<GridWrap> wrap = gridWrapNamed(wrapName);
  if (!wrap) albedo.fail("wrap_mode", "'" + wrapName + "' is not a wrap mode (clamp, repeat, mirror)");
  PlacedGrid g = placedGrid(albedo, ctx);
  const int channels = g.grid.channels();
  if (channels != 1 && channels != 3)
    albedo.fail("file", "an albedo grid has 3 channels (linear RGB) or 1 (grey), '" + albedo.string("file") + "' has " +
                            std::to_string(channels));
  for (int c = 0; c < channels; ++c)
    if (g.grid.maximum(c) > 1.0f)
      albedo.fail("file", "albedo values must lie in [0, 1]; channel " + std::to_string(c) + " reaches " +
                              std::to_string(g.grid.maximum(c)));
  return std::make_shared<GridAlbedo>(std::move(g.grid), g.toWorld, g.useGridBox, *wrap);
}

}  // namespace

std::unique_ptr<Medium> parseMedium(const std::string& name, const nlohmann::json& v, const SpectrumContext& ctx,
                                    const std::string& pointer, WavelengthRange range) {
  JsonFields f(v, ctx.file, pointer);
  const std::string type = f.string("type");
  if (type != "homogeneous" && type != "heterogeneous")
    f.fail("type", "'" + type + "' is not a medium type (homogeneous, heterogeneous)");
  if (type != "homogeneous" && f.has("albedo_grid"))
    f.fail("albedo_grid", "only a homogeneous medium takes an albedo grid (media.md §7)");
  std::shared_ptr<const DensityField> density;
  if (type == "heterogeneous") {
    density = densityGrid(f, ctx);
    // Camera paths' source-seeking free flights (media.md eq. 6b) need a homogeneous medium.
    if (f.has("fluorophores")) f.fail("fluorophores", "a heterogeneous medium cannot fluoresce yet (media.md §4)");
  }
  MediumParams p;
  std::shared_ptr<const AlbedoField> albedo;
  if (f.has("albedo_grid")) {
    // σ_t alone, split at each point by the grid (media.md eq. 11): it is σ_a + σ_s with σ_s 0.
    if (f.has("fluorophores")) f.fail("albedo_grid", "a medium with fluorophores takes no albedo grid (media.md §7)");
    for (const char* key : {"sigma_a", "sigma_s"})
      if (f.has(key)) f.fail(key, "with albedo_grid, give sigma_t (the grid splits it into scattering and absorption)");
    if (!f.has("sigma_t")) f.fail("albedo_grid", "needs sigma_t (the extinction the grid splits)");
    albedo = albedoGrid(f, ctx);
    p.absorption = parseSpectrum(f.get("sigma_t"), ctx, f.path("sigma_t"));
  } else {
    if (f.has("sigma_t")) f.fail("sigma_t", "is read with albedo_grid only (otherwise give sigma_a and sigma_s)");
    p.absorption = spectrumOr(f, "sigma_a", ctx, 0.0f);
    p.scattering = spectrumOr(f, "sigma_s", ctx, 0.0f);
  }
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
    if (albedo && field == "sigma_a") field = "sigma_t";  // given as sigma_t (above)
    if (field.starts_with("fluorophores[")) {
      const size_t close = field.find(']');
      const std::string k = field.substr(13, close - 13), key = field.substr(close + 2);
      const bool molar = key == "sigma_f" && v["fluorophores"][std::stoul(k)].contains("molar_absorption");
      field = "fluorophores/" + k + "/" + (molar ? "molar_absorption" : key);
    }
    throw InputError(ctx.file, pointer + "/" + field, problem.substr(colon + 2));
  }
  return std::make_unique<Medium>(name, std::move(p), range, std::move(density), std::move(albedo));
}

}  // namespace kasha
