#include "scene/mitsuba/xml_texture.h"

namespace kasha::mitsuba {

using nlohmann::json;

json bitmapTexture(XmlImport& xml, pugi::xml_node node) {
  Plugin t(xml, node);
  if (t.type() != "bitmap") t.fail("unsupported texture plugin (bitmap)");
  const pugi::xml_node file = t.property("filename");
  if (!file) t.fail("missing property 'filename'");
  const std::string name = xml.attribute(file, "value");
  json out = {{"file", xml.resolve(file, name)}, {"channel", "rgb"}};
  const std::string filter = t.string("filter_type", "bilinear");
  if (filter != "bilinear" && filter != "nearest") t.fail("filter_type '" + filter + "' is not bilinear or nearest");
  out["filter"] = filter;
  const std::string wrap = t.string("wrap_mode", "repeat");
  if (wrap != "repeat" && wrap != "mirror" && wrap != "clamp")
    t.fail("wrap_mode '" + wrap + "' is not repeat, mirror or clamp");
  out["wrap"] = wrap;
  out["encoding"] = t.boolean("raw", false) ? "linear" : "srgb";
  t.finish();
  return out;
}

}  // namespace kasha::mitsuba
