#pragma once
// The scattering function at one hit, as integrators use it: a small value (no heap allocation)
// that a Material builds from the hit's context (materials/material.h). Directions passed to it
// are local to its shading frame (toLocal/toWorld); the physical order, transport modes, two
// sampling stages and densities are those of BsdfModel (materials/bsdf_model.h).
//
// Model storage: an untextured material's Bsdf points at the material itself (a model that lives
// as long as the scene). A textured material builds a model for the hit from its texture lookups
// (materials/textured_material.h) inside the Bsdf: inPlace() copies it into kInPlaceBytes of
// storage that every Bsdf carries but only such a Bsdf touches, so building, copying and
// destroying an untextured material's Bsdf costs what it did before (a pointer and two frames).
// A per-hit model must be trivially destructible and fit the storage (checked at compile time).
#include <cmath>
#include <cstddef>
#include <new>
#include <span>
#include <type_traits>

#include "core/texture.h"
#include "materials/bsdf_model.h"
#include "materials/shading_normal.h"

namespace kasha {

// What a material may depend on at a hit; read while the Bsdf is built (a Bsdf keeps the frames only).
struct HitContext {
  Vec2 uv{0.0f};        // texture coordinates (computed for textured materials only, else 0)
  Frame geometric{};    // world frame of the geometric normal (z = n_g)
  Frame shading{};      // world frame of the shading normal; the geometric one until shading normals exist
  std::span<const float> wavelengths;  // the path's wavelengths here (hero: every lane; else one)
  MeshPoint mesh{};     // the shape, triangle and barycentrics, for mesh-attribute textures
  TexturePoint texturePoint() const { return {uv, mesh}; }
  // ∂p/∂u and ∂p/∂v of the surface's texture parameterisation (Shape::uvDerivatives; textured
  // materials only, else 0): the tangents of normal and bump maps (materials/normal_perturbation.h).
  Vec3 dpdu{0.0f}, dpdv{0.0f};
};

class Bsdf {
 public:
  // Bytes of in-place storage for a per-hit model (the largest, coated_fluorescent's, takes 80 on
  // x86-64; inPlace() checks at compile time).
  static constexpr size_t kInPlaceBytes = 96;

  // `model` must outlive the Bsdf (the material's own).
  Bsdf(const BsdfModel& model, const HitContext& ctx)
      : model_(&model), geometric_(ctx.geometric), shading_(ctx.shading), correction_(ctx.geometric, ctx.shading),
        flags_(model.flags()) {}
  // A Bsdf holding its own copy of `model`, built for this hit (a textured material's).
  template <class Model>
  static Bsdf inPlace(const Model& model, const HitContext& ctx) {
    static_assert(std::is_base_of_v<BsdfModel, Model> && std::is_trivially_destructible_v<Model>);
    static_assert(sizeof(Model) <= kInPlaceBytes && alignof(Model) <= alignof(std::max_align_t));
    Bsdf b(model, ctx);
    b.clone_ = [](const BsdfModel& from, void* to) -> const BsdfModel* {
      return ::new (to) Model(static_cast<const Model&>(from));
    };
    b.model_ = b.clone_(model, b.storage_);
    return b;
  }
  Bsdf(const Bsdf& o)
      : model_(o.model_), geometric_(o.geometric_), shading_(o.shading_), correction_(o.correction_),
        flags_(o.flags_), frontOnly_(o.frontOnly_), clone_(o.clone_) {
    if (clone_) model_ = clone_(*o.model_, storage_);
  }
  Bsdf& operator=(const Bsdf& o) {
    if (this != &o) {
      geometric_ = o.geometric_, shading_ = o.shading_, correction_ = o.correction_, flags_ = o.flags_;
      frontOnly_ = o.frontOnly_;
      clone_ = o.clone_;
      model_ = clone_ ? clone_(*o.model_, storage_) : o.model_;
    }
    return *this;
  }

  // A one-sided surface (Material::oneSided; Mitsuba's BSDFs that are black from behind): every
  // query below gives nothing unless both directions lie on the front of the shading normal (local
  // z > 0), as Mitsuba checks cos θ_i > 0 and cos θ_o > 0.
  void restrictToFront() { frontOnly_ = true; }

  // DeltaDirection, Fluorescent, WavelengthDependentDirection: known before anything is sampled.
  BsdfFlags flags() const { return flags_; }
  bool has(BsdfFlags f) const { return kasha::has(flags_, f); }
  const Frame& geometricFrame() const { return geometric_; }
  // The factor that turns f into the integrand of the scattering integral for a local direction
  // (the one sampled, or toward a light or the camera): |cos θ| at a surface, 1 at a medium point.
  float cosineFactor(const Vec3& w) const { return has(BsdfFlags::Volume) ? 1.0f : std::abs(w.z); }
  // The model it evaluates (for tests and tools that inspect parameters).
  const BsdfModel& model() const { return *model_; }
  // |ω_i·n_s|/|ω_i·n_g| of light arriving along local ω_i (1 without a shading normal): what turns
  // eval() into Veach's f_s where the incident flux is known instead of a sampled ω_i (photons).
  float incidentShadingRatio(const Vec3& wi) const { return correction_.incidentRatio(wi); }
  // World ↔ the local (shading) frame every query below uses.
  Vec3 toLocal(const Vec3& world) const { return shading_.toLocal(world); }
  Vec3 toWorld(const Vec3& local) const { return shading_.toWorld(local); }

  // f in physical order (ω_i, λ_i → ω_o, λ_o) of one lobe; per nm if fluorescent, deltas left out.
  // With a shading normal, f·|cos θ_s| of the sampled direction is Veach's f_s (shading_normal.h).
  float eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const {
    if (!front(wi) || !front(wo)) return 0.0f;
    const float c = correction_.factor(query.mode, wi, wo);
    return c > 0.0f ? c * model_->eval(query, wi, wo) : 0.0f;
  }
  // Spectral stage: from the known wavelength, the lobe (fluorescent exactly when u < P) and the
  // unknown wavelength; pdf is the lobe's probability × (fluorescent) its per-nm density.
  SpectralChoice sampleSpectral(TransportMode mode, float lambdaKnown, float u) const {
    return model_->sampleSpectral(mode, lambdaKnown, u);
  }
  // That stage's density of (lobe, lambdaOther): a probability (elastic) or per nm (fluorescent).
  float spectralPdf(TransportMode mode, float lambdaKnown, float lambdaOther, SpectralLobe lobe) const {
    return model_->spectralPdf(mode, lambdaKnown, lambdaOther, lobe);
  }
  // Probability of the fluorescent lobe given the known wavelength (the model's own, never a
  // default): 1 − spectralPdf(mode, λ, λ, Elastic) wherever anything scatters.
  float fluorescenceProbability(TransportMode mode, float lambdaKnown) const {
    return model_->fluorescenceProbability(mode, lambdaKnown);
  }
  // Directional stage given the lobe and both wavelengths: the unknown direction, its density
  // per steradian (a probability if specular).
  std::optional<DirectionSample> sampleDirection(const ScatterQuery& query, const Vec3& wKnown, Vec2 u) const {
    if (!correction_.consistent(wKnown) || !front(wKnown)) return std::nullopt;
    std::optional<DirectionSample> ds = model_->sampleDirection(query, wKnown, u);
    if (ds && (!correction_.consistent(ds->w) || !front(ds->w))) return std::nullopt;
    return ds;
  }
  // That stage's density of wSampled, per steradian.
  float directionPdf(const ScatterQuery& query, const Vec3& wKnown, const Vec3& wSampled) const {
    if (!front(wKnown) || !front(wSampled)) return 0.0f;
    return model_->directionPdf(query, wKnown, wSampled);
  }
  // Both stages (u.x spectral, u.y/u.z direction): value, density in this mode and the reverse.
  std::optional<ScatterSample> sample(TransportMode mode, const Vec3& wKnown, float lambdaKnown, Vec3 u) const {
    if (!correction_.consistent(wKnown) || !front(wKnown)) return std::nullopt;
    std::optional<ScatterSample> s = model_->sample(mode, wKnown, lambdaKnown, u);
    if (s && !front(s->w)) return std::nullopt;
    if (!s || !correction_.active) return s;
    const bool radiance = mode == TransportMode::Radiance;
    s->f *= correction_.factor(mode, radiance ? s->w : wKnown, radiance ? wKnown : s->w);
    return s->f > 0.0f ? s : std::nullopt;
  }
  // Both densities (this mode, reverse) of an event in physical order: spectral × directional.
  ScatterDensity pdf(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const {
    if (!front(wi) || !front(wo)) return {};
    return model_->pdf(query, wi, wo);
  }

 private:
  bool front(const Vec3& w) const { return !frontOnly_ || w.z > 0.0f; }

  const BsdfModel* model_;
  Frame geometric_, shading_;
  ShadingCorrection correction_;
  BsdfFlags flags_;
  bool frontOnly_ = false;
  // Copies a per-hit model into storage_; null when model_ lives outside the Bsdf.
  const BsdfModel* (*clone_)(const BsdfModel& from, void* to) = nullptr;
  alignas(std::max_align_t) std::byte storage_[kInPlaceBytes];
};

}  // namespace kasha
