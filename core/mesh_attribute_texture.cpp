#include "core/mesh_attribute_texture.h"

#include <stdexcept>

#include "core/shape.h"

namespace kasha {

MeshAttributeTexture::MeshAttributeTexture(std::string name, int channels) : name_(std::move(name)), channels_(channels) {
  if (!name_.starts_with("vertex_") && !name_.starts_with("face_"))
    throw std::invalid_argument("mesh attribute '" + name_ + "': the name must start with vertex_ or face_");
  if (channels != 1 && channels != 3) throw std::invalid_argument("mesh attribute: channels must be 1 or 3");
}

Vec3 MeshAttributeTexture::at(const TexturePoint& p) const {
  if (!p.mesh.shape) return Vec3(0.0f);
  const MeshAttribute* a = p.mesh.shape->attribute(name_);
  return a ? p.mesh.shape->attributeAt(*a, p.mesh.prim, p.mesh.bary) : Vec3(0.0f);
}

}  // namespace kasha
