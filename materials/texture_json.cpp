#include "materials/texture_json.h"

#include <cmath>
#include <stdexcept>

#include "core/checkerboard_texture.h"
#include "core/error.h"
#include "core/json_parse.h"
#include "core/mesh_attribute_texture.h"

namespace kasha {
namespace {

// What a texture field holds: one channel; one or three (a reflectance); three (normals).
enum class TextureUse { Scalar, Reflectance, Normals };

// {"type": "image"} (f) or a file name (f null: `file`): an image (core/texture.h). Reflectances
// and normals allow "channel": "rgb" (the default and the only choice for normals). key: the field
// below `parent`, for messages.
std::shared_ptr<const Texture> imageTexture(JsonFields& parent, const std::string& key, std::string file, JsonFields* f,
                                            const SpectrumContext& ctx, TextureUse use) {
  const bool rgb = use != TextureUse::Scalar;
  TextureChannel channel = use == TextureUse::Normals ? TextureChannel::Rgb : TextureChannel::Mean;
  TextureWrap wrap = TextureWrap::Repeat;
  TextureFilter filter = TextureFilter::Bilinear;
  TextureEncoding encoding = TextureEncoding::Linear;
  if (f) {
    const std::string name = f->string("channel", use == TextureUse::Normals ? "rgb" : "mean");
    const std::optional<TextureChannel> c = rgb && name == "rgb" ? TextureChannel::Rgb : parseTextureChannel(name);
    if (use == TextureUse::Normals && name != "rgb") f->fail("channel", "a normal map's channel is rgb");
    if (!c) f->fail("channel", "unknown channel '" + name + (rgb ? "' (mean, luminance, r, g, b, a, rgb)" : "' (mean, luminance, r, g, b, a)"));
    channel = *c;
    const std::string wrapName = f->string("wrap", "repeat");
    const std::optional<TextureWrap> w = parseTextureWrap(wrapName);
    if (!w) f->fail("wrap", "unknown wrap mode '" + wrapName + "' (repeat, clamp, mirror)");
    wrap = *w;
    const std::string filterName = f->string("filter", "bilinear");
    const std::optional<TextureFilter> fl = parseTextureFilter(filterName);
    if (!fl) f->fail("filter", "unknown filter '" + filterName + "' (bilinear, nearest)");
    filter = *fl;
    const std::string encodingName = f->string("encoding", "linear");
    const std::optional<TextureEncoding> e = parseTextureEncoding(encodingName);
    if (!e) f->fail("encoding", "unknown encoding '" + encodingName + "' (linear, srgb)");
    encoding = *e;
  }
  const std::string path = ctx.resolve(file);
  try {
    if (ctx.textures) return ctx.textures->load(path, channel, wrap, filter, encoding);
    return TextureLoader(ctx.memoryLimit).load(path, channel, wrap, filter, encoding);
  } catch (const InputError& e) {  // names the file already
    parent.fail(key, e.what());
  } catch (const std::runtime_error& e) {  // also MemoryLimitError
    parent.fail(key, "'" + path + "': " + e.what());
  }
}

// A checkerboard's value: a number in [0, 1], or (rgb) [r, g, b] in [0, 1]; *colour is set if
// it is a colour.
Vec3 checkerValue(JsonFields& f, const std::string& key, float fallback, bool rgb, bool* colour) {
  if (!f.has(key)) return Vec3(fallback);
  const nlohmann::json& v = f.get(key);
  Vec3 c;
  if (v.is_number()) {
    c = Vec3(v.get<float>());
  } else if (rgb && v.is_array()) {
    c = f.vec3(key);
    *colour = true;
  } else {
    f.fail(key, rgb ? "expected a number or [r, g, b]" : "expected a number (a scalar parameter's texture)");
  }
  for (int k = 0; k < 3; ++k)
    if (!(c[k] >= 0.0f && c[k] <= 1.0f)) f.fail(key, "values must lie in [0, 1]");
  return c;
}

// "to_uv": [[a, b, c], [d, e, f]], u' = a·u + b·v + c, v' = d·u + e·v + f.
UvTransform uvTransform(JsonFields& f) {
  UvTransform t;
  if (!f.has("to_uv")) return t;
  const nlohmann::json& rows = f.get("to_uv");
  const auto isRow = [](const nlohmann::json& r) {
    if (!r.is_array() || r.size() != 3) return false;
    for (const nlohmann::json& x : r)
      if (!x.is_number() || !std::isfinite(x.get<double>())) return false;
    return true;
  };
  if (!rows.is_array() || rows.size() != 2 || !isRow(rows[0]) || !isRow(rows[1]))
    f.fail("to_uv", "expected two rows of three finite numbers, [[a, b, c], [d, e, f]]");
  for (int r = 0; r < 2; ++r) {
    t.linear[0][r] = rows[r][0].get<float>();
    t.linear[1][r] = rows[r][1].get<float>();
    t.offset[r] = rows[r][2].get<float>();
  }
  return t;
}

// The texture `v` at "<key>" below `parent` (texture_json.h), for `use` (colours allowed unless Scalar).
std::shared_ptr<const Texture> parseTexture(JsonFields& parent, const std::string& key, const nlohmann::json& v,
                                            const SpectrumContext& ctx, TextureUse use) {
  if (v.is_string()) return imageTexture(parent, key, v.get<std::string>(), nullptr, ctx, use);
  const bool rgb = use != TextureUse::Scalar;
  if (!v.is_object())
    parent.fail(key, "expected an image file name or a texture object ({\"file\": ...} or {\"type\": ...}), got " +
                         jsonTypeName(v));
  JsonFields f(v, ctx.file, parent.path(key));
  const std::string type = f.string("type", "image");
  std::shared_ptr<const Texture> t;
  if (type == "image") {
    t = imageTexture(parent, key, f.string("file"), &f, ctx, use);
  } else if (type == "checkerboard") {
    bool colour = false;
    const Vec3 c0 = checkerValue(f, "color0", 0.4f, rgb, &colour), c1 = checkerValue(f, "color1", 0.2f, rgb, &colour);
    t = std::make_shared<const CheckerboardTexture>(c0, c1, colour ? 3 : 1, uvTransform(f));
  } else if (type == "mesh_attribute") {
    const std::string name = f.string("name");
    if (!name.starts_with("vertex_") && !name.starts_with("face_"))
      f.fail("name", "'" + name + "' is not a mesh attribute's name (vertex_... or face_...)");
    t = std::make_shared<const MeshAttributeTexture>(name, rgb ? 3 : 1);
  } else {
    f.fail("type", "unknown texture type '" + type + "' (image, checkerboard, mesh_attribute)");
  }
  f.finish();
  return t;
}

}  // namespace

ScalarTexture parseScalarTexture(JsonFields& f, const std::string& key, const SpectrumContext& ctx) {
  if (!f.has(key)) return {};
  return ScalarTexture{parseTexture(f, key, f.get(key), ctx, TextureUse::Scalar)};
}

ReflectanceTexture parseReflectanceTexture(JsonFields& f, const std::string& key, const SpectrumContext& ctx) {
  if (!f.has(key)) return {};
  return ReflectanceTexture{parseTexture(f, key, f.get(key), ctx, TextureUse::Reflectance)};
}

AlphaTexture parseAlphaTexture(JsonFields& f, const std::string& key, const SpectrumContext& ctx) {
  if (!f.has(key)) return {};
  const nlohmann::json& v = f.get(key);
  if (!v.is_array()) {
    const ScalarTexture both{parseTexture(f, key, v, ctx, TextureUse::Scalar)};
    return {both, both};
  }
  if (v.size() != 2) f.fail(key, "expected one texture (both axes) or two, [α_x's, α_y's] (null: none)");
  AlphaTexture t;
  if (!v[0].is_null()) t.x.texture = parseTexture(f, key + "/0", v[0], ctx, TextureUse::Scalar);
  if (!v[1].is_null()) t.y.texture = parseTexture(f, key + "/1", v[1], ctx, TextureUse::Scalar);
  return t;
}

std::shared_ptr<const Texture> parseRequiredTexture(JsonFields& f, const std::string& key, const SpectrumContext& ctx,
                                                    bool normals) {
  if (!f.has(key)) f.fail(key, "missing required field");
  std::shared_ptr<const Texture> t = parseTexture(f, key, f.get(key), ctx, normals ? TextureUse::Normals : TextureUse::Scalar);
  if (normals && t->channels() != 3) f.fail(key, "a normal map needs three channels (a colour)");
  if (!normals && !t->readsUv()) f.fail(key, "a height is read at texture coordinates (a mesh attribute has no slope)");
  return t;
}

}  // namespace kasha
