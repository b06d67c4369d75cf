#pragma once
// A mesh attribute as a texture (Mitsuba 3 docs: mesh_attribute): the value a mesh file gives per
// vertex (interpolated with the barycentrics) or per triangle, at the hit (Shape::attributeAt).
// The texture names the attribute; every shape its material is on must carry it (the scene loader
// checks), with one channel where a scalar reads it. A one-channel attribute read as a colour is
// its grey. Without a mesh at the point (TexturePoint::mesh.shape null) it reads 0.
#include <string>

#include "core/texture.h"

namespace kasha {

class MeshAttributeTexture : public Texture {
 public:
  // name: "vertex_…" or "face_…" (std::invalid_argument otherwise); channels: 1 where a scalar
  // reads it, 3 where a colour does.
  MeshAttributeTexture(std::string name, int channels);
  int channels() const override { return channels_; }
  float scalar(const TexturePoint& p) const override { return at(p).x; }
  Vec3 rgb(const TexturePoint& p) const override { return at(p); }
  bool readsUv() const override { return false; }
  std::string meshAttribute() const override { return name_; }

 private:
  Vec3 at(const TexturePoint& p) const;
  std::string name_;
  int channels_;
};

}  // namespace kasha
