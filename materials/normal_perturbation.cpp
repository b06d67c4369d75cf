#include "materials/normal_perturbation.h"

#include <cmath>
#include <stdexcept>

namespace kasha {
namespace {

// The frame (s, n × s, n) with s the part of dpdu orthogonal to the unit normal n (Gram–Schmidt);
// any frame around n where dpdu has no such part.
Frame tangentFrame(const Vec3& n, const Vec3& dpdu) {
  const Vec3 s = dpdu - glm::dot(n, dpdu) * n;
  const float len = glm::length(s);
  if (!(len > 1e-6f * glm::length(dpdu)) || !std::isfinite(len)) return Frame::fromNormal(n);
  const Vec3 su = s / len;
  return {su, glm::cross(n, su), n};
}

}  // namespace

Bsdf PerturbedNormalMaterial::bsdf(const HitContext& ctx) const {
  const Frame tangent = tangentFrame(ctx.shading.n, ctx.dpdu);
  const Vec3 local = tangentNormal(ctx, tangent);
  const float len = glm::length(local);
  if (!(len > 0.0f) || !std::isfinite(len) || local / len == Vec3(0.0f, 0.0f, 1.0f)) return nested_->bsdf(ctx);
  const Vec3 n = glm::normalize(tangent.toWorld(local / len));
  if (!(glm::dot(n, ctx.geometric.n) > 0.0f)) return nested_->bsdf(ctx);
  HitContext tilted = ctx;
  tilted.shading = tangentFrame(n, ctx.dpdu);
  return nested_->bsdf(tilted);
}

std::vector<const Texture*> PerturbedNormalMaterial::textures() const {
  std::vector<const Texture*> out = nested_->textures();
  out.push_back(map_.get());
  return out;
}

NormalMapMaterial::NormalMapMaterial(std::unique_ptr<Material> nested, std::shared_ptr<const Texture> normals)
    : PerturbedNormalMaterial(std::move(nested), normals) {
  if (!normals || normals->channels() != 3) throw std::invalid_argument("a normal map needs a three-channel texture");
}

// A tangent-space normal map stores (n + 1)/2 (Mitsuba 3 docs: normalmap).
Vec3 NormalMapMaterial::tangentNormal(const HitContext& ctx, const Frame&) const {
  return 2.0f * map().rgb(ctx.texturePoint()) - 1.0f;
}

BumpMapMaterial::BumpMapMaterial(std::unique_ptr<Material> nested, std::shared_ptr<const Texture> height, float scale)
    : PerturbedNormalMaterial(std::move(nested), height), scale_(scale) {
  if (!height || height->channels() != 1 || !height->readsUv())
    throw std::invalid_argument("a bump map needs a one-channel texture read at texture coordinates");
}

// The displaced surface's tangents, their components along n replaced by scale·∂h/∂u and
// scale·∂h/∂v (Mitsuba 3 docs: bumpmap), and their cross product, on the geometric normal's side.
Vec3 BumpMapMaterial::tangentNormal(const HitContext& ctx, const Frame& tangent) const {
  const Vec2 slope = scale_ * map().scalarGradient(ctx.texturePoint());
  Vec3 dpdu = tangent.toLocal(ctx.dpdu), dpdv = tangent.toLocal(ctx.dpdv);
  dpdu.z = slope.x;
  dpdv.z = slope.y;
  const Vec3 n = glm::cross(dpdu, dpdv);
  return glm::dot(n, tangent.toLocal(ctx.geometric.n)) < 0.0f ? -n : n;
}

}  // namespace kasha
