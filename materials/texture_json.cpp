#include "materials/texture_json.h"

#include <stdexcept>

#include "core/error.h"
#include "core/json_parse.h"

namespace kasha {
namespace {

// What a texture field holds: one channel; one or three (a reflectance); three (normals).
enum class TextureUse { Scalar, Reflectance, Normals };

// The image of "<key>" (texture_json.h); nullptr when absent.
std::shared_ptr<const ImageTexture> parseTexture(JsonFields& parent, const std::string& key, const SpectrumContext& ctx,
                                                 TextureUse use) {
  if (!parent.has(key)) return nullptr;
  const nlohmann::json& v = parent.get(key);
  std::string file;
  const bool rgb = use != TextureUse::Scalar;
  TextureChannel channel = use == TextureUse::Normals ? TextureChannel::Rgb : TextureChannel::Mean;
  TextureWrap wrap = TextureWrap::Repeat;
  TextureFilter filter = TextureFilter::Bilinear;
  TextureEncoding encoding = TextureEncoding::Linear;
  if (v.is_string()) {
    file = v.get<std::string>();
  } else if (v.is_object()) {
    JsonFields f(v, ctx.file, parent.path(key));
    file = f.string("file");
    const std::string name = f.string("channel", use == TextureUse::Normals ? "rgb" : "mean");
    const std::optional<TextureChannel> c = rgb && name == "rgb" ? TextureChannel::Rgb : parseTextureChannel(name);
    if (use == TextureUse::Normals && name != "rgb") f.fail("channel", "a normal map's channel is rgb");
    if (!c) f.fail("channel", "unknown channel '" + name + (rgb ? "' (mean, r, g, b, a, rgb)" : "' (mean, r, g, b, a)"));
    channel = *c;
    const std::string wrapName = f.string("wrap", "repeat");
    const std::optional<TextureWrap> w = parseTextureWrap(wrapName);
    if (!w) f.fail("wrap", "unknown wrap mode '" + wrapName + "' (repeat, clamp, mirror)");
    wrap = *w;
    const std::string filterName = f.string("filter", "bilinear");
    const std::optional<TextureFilter> fl = parseTextureFilter(filterName);
    if (!fl) f.fail("filter", "unknown filter '" + filterName + "' (bilinear, nearest)");
    filter = *fl;
    const std::string encodingName = f.string("encoding", "linear");
    const std::optional<TextureEncoding> e = parseTextureEncoding(encodingName);
    if (!e) f.fail("encoding", "unknown encoding '" + encodingName + "' (linear, srgb)");
    encoding = *e;
    f.finish();
  } else {
    parent.fail(key, "expected an image file name or {\"file\": ..., \"channel\": ...}, got " + jsonTypeName(v));
  }
  const std::string path = (!file.empty() && file[0] == '/') ? file : ctx.baseDir + "/" + file;
  try {
    if (ctx.textures) return ctx.textures->load(path, channel, wrap, filter, encoding);
    return TextureLoader(ctx.memoryLimit).load(path, channel, wrap, filter, encoding);
  } catch (const InputError& e) {  // names the file already
    parent.fail(key, e.what());
  } catch (const std::runtime_error& e) {  // also MemoryLimitError
    parent.fail(key, "'" + path + "': " + e.what());
  }
}

}  // namespace

ScalarTexture parseScalarTexture(JsonFields& f, const std::string& key, const SpectrumContext& ctx) {
  return ScalarTexture{parseTexture(f, key, ctx, TextureUse::Scalar)};
}

ReflectanceTexture parseReflectanceTexture(JsonFields& f, const std::string& key, const SpectrumContext& ctx) {
  return ReflectanceTexture{parseTexture(f, key, ctx, TextureUse::Reflectance)};
}

std::shared_ptr<const ImageTexture> parseRequiredTexture(JsonFields& f, const std::string& key, const SpectrumContext& ctx,
                                                         bool normals) {
  if (!f.has(key)) f.fail(key, "missing required field");
  return parseTexture(f, key, ctx, normals ? TextureUse::Normals : TextureUse::Scalar);
}

}  // namespace kasha
