#pragma once
// The scattering function at one point of a surface, in the local frame (docs/transport.md §1–2:
// elastic and fluorescent lobes, the transport mode).
// Materials build a Bsdf (materials/bsdf.h) per hit around one of these models; integrators use
// the Bsdf, and the model tests call the model directly.
//
// Conventions
// - A query always names the physical order: light arrives along ω_i at λ_i and leaves along ω_o
//   at λ_o. Both directions point away from the surface, in the local (shading) frame, z up.
//   Models decide themselves what the two sides of a surface mean.
// - TransportMode says which side is known, and is never defaulted:
//     Radiance   (camera subpaths): ω_o, λ_o known; ω_i, λ_i sampled.
//     Importance (light subpaths, photons): ω_i, λ_i known; ω_o, λ_o sampled.
// - A lobe is elastic (λ_o = λ_i, a Dirac delta in wavelength, whose delta is left out of every
//   value and density, exactly like a specular delta in direction) or fluorescent (a density per
//   nm in the sampled wavelength). Which one an event used is a flag, never a comparison of
//   wavelengths.
// - Sampling runs in two stages: the spectral event (lobe and unknown wavelength, from the known
//   wavelength alone) and then the direction given that event. Integrators may use the stages
//   separately (next-event estimation shares the spectral event with direction sampling) or
//   together through sample()/pdf(), whose densities are the products.
#include <cstdint>
#include <optional>

#include "core/math.h"

namespace kasha {

enum class TransportMode : uint8_t { Radiance, Importance };
inline TransportMode flip(TransportMode m) {
  return m == TransportMode::Radiance ? TransportMode::Importance : TransportMode::Radiance;
}
const char* toString(TransportMode m);

enum class SpectralLobe : uint8_t { Elastic, Fluorescent };

// What a scattering function is, as a set of bits (a model's are fixed; a material's are the union
// over its surface).
enum class BsdfFlags : uint8_t {
  None = 0,
  DeltaDirection = 1 << 0,  // every lobe is a Dirac delta in direction: no next-event estimation
  Fluorescent = 1 << 1,     // some lobe changes the wavelength
  // The direction sampled for an elastic event (or its density) depends on the wavelength (a
  // dispersive index, a lobe choice weighted by a spectrum): a direction drawn for one wavelength
  // is not one drawn for another, so hero wavelengths end their secondaries before it.
  // (A fluorescent lobe's direction density never depends on the wavelengths: every model's is
  // diffuse, and wavelength lanes rely on it.)
  WavelengthDependentDirection = 1 << 2,
  // Kasha's rule: the fluorescent lobe's spectral density is P_fl(λ_known)·q(λ_other), q the same
  // for every known wavelength (the absorption's density for a camera path, the emission's for a
  // light path; Jung18 eq. 3, Zhdanov's E·A), so the mixture of the lanes' excitation densities at
  // a fluorescent event is q itself, evaluated once (integrators/wavelength_lanes.cpp).
  FactorisedFluorescence = 1 << 3,
  // A point inside a participating medium (materials/volume_scattering.h): f is the volume's
  // scattering kernel per unit length, directions range over the whole sphere, and no cosine
  // projects it (Bsdf::cosineFactor).
  Volume = 1 << 4,
  // Some lobes, not all, are Dirac deltas in direction (an opacity mask's pass-through, a blend
  // with a mirror): the bidirectional engine neither connects nor merges at such a point, since a
  // connection there could not make a path through its delta (integrators/bidirectional/path_vertex.h).
  DeltaLobe = 1 << 5,
};
constexpr BsdfFlags operator|(BsdfFlags a, BsdfFlags b) { return BsdfFlags(uint8_t(a) | uint8_t(b)); }
constexpr bool has(BsdfFlags set, BsdfFlags f) { return (uint8_t(set) & uint8_t(f)) != 0; }
// `f` if `on`, else None.
constexpr BsdfFlags flagIf(bool on, BsdfFlags f) { return on ? f : BsdfFlags::None; }

// What a query of the directional stage is about (compare Mitsuba 3's BSDFContext): the transport
// mode, which names the sampled direction, and the spectral event, its lobe and both wavelengths in
// physical order (for an elastic lobe the two are equal).
struct ScatterQuery {
  TransportMode mode;
  SpectralLobe lobe;
  float lambdaIn;
  float lambdaOut;
};

// Outcome of the spectral stage.
struct SpectralChoice {
  SpectralLobe lobe = SpectralLobe::Elastic;
  float lambda = 0.0f;  // the unknown side's wavelength (equal to the known one when elastic)
  float pdf = 0.0f;     // P(lobe | known λ) × (per-nm density of lambda, fluorescent only)
};

// Outcome of the directional stage.
struct DirectionSample {
  Vec3 w;                 // the unknown side's direction, local frame
  float pdf = 0.0f;       // per steradian (for a specular lobe: the discrete probability)
  bool specular = false;  // Dirac delta in direction
};

// Both stages together. The reverse density is the probability of sampling the known side
// from the sampled one in the other transport mode (what BDPT's MIS needs).
struct ScatterSample {
  Vec3 w;
  float lambda = 0.0f;
  SpectralLobe lobe = SpectralLobe::Elastic;
  bool specular = false;
  float f = 0.0f;       // value of f (deltas left out); per nm when fluorescent
  float pdf = 0.0f;     // spectral pdf × direction pdf, this mode
  float pdfRev = 0.0f;  // spectral pdf × direction pdf, the other mode, roles swapped
};

struct ScatterDensity {
  float pdf = 0.0f;
  float pdfRev = 0.0f;
};

class BsdfModel {
 public:
  // f(λ_i, ω_i, ω_o, λ_o) of the query's lobe: for Elastic, λ_i = λ_o is implied and lambdaIn is
  // used; for Fluorescent, the density per nm of leaving at λ_o. Local directions.
  // The query's mode names the direction that was sampled (ω_i in Radiance mode, ω_o in Importance mode).
  // It matters only for a specular lobe, whose value is the coefficient of the Dirac delta in the
  // solid angle of that sampled direction, so that f·|cos θ_sampled|/pdf is the path weight in
  // both modes. Refraction maps solid angles with dω_o/dω_i = η_i²|cos θ_i| / (η_o²|cos θ_o|), so
  // there the two coefficients differ (Veach97 §5.2); every non-specular f is the same in both.
  virtual float eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const = 0;

  // Spectral stage: chooses the lobe and the unknown wavelength given the known one (λ_o in
  // Radiance mode, λ_i in Importance mode): the fluorescent lobe exactly when
  // u < fluorescenceProbability(mode, λ), its wavelength then drawn with u/P. Returns pdf 0 when
  // nothing is scattered.
  virtual SpectralChoice sampleSpectral(TransportMode mode, float lambdaKnown, float u) const = 0;
  // Density of that choice: lambdaOther is the sampled side's wavelength.
  virtual float spectralPdf(TransportMode mode, float lambdaKnown, float lambdaOther, SpectralLobe lobe) const = 0;
  // The probability with which sampleSpectral chooses the fluorescent lobe given the known
  // wavelength: 1 − spectralPdf(mode, λ, λ, Elastic) wherever anything is scattered. An integrator
  // that draws the unknown wavelength of the fluorescent lobe from its own density p(λ) (a
  // wavelength strategy) samples the event with density P·p(λ) (eval() is per nm).
  virtual float fluorescenceProbability(TransportMode mode, float lambdaKnown) const = 0;

  // Directional stage given the query's spectral event (lobe and both wavelengths, which a
  // dispersive model needs); wKnown is ω_o (Radiance) or ω_i (Importance). The density is per
  // steradian (for a specular lobe, the discrete probability).
  virtual std::optional<DirectionSample> sampleDirection(const ScatterQuery& query, const Vec3& wKnown,
                                                         Vec2 u) const = 0;
  virtual float directionPdf(const ScatterQuery& query, const Vec3& wKnown, const Vec3& wSampled) const = 0;

  // DeltaDirection, Fluorescent, WavelengthDependentDirection (BsdfFlags).
  virtual BsdfFlags flags() const = 0;

  // Both stages: u.x for the spectral stage, (u.y, u.z) for the direction.
  std::optional<ScatterSample> sample(TransportMode mode, const Vec3& wKnown, float lambdaKnown, Vec3 u) const;
  // Densities of an event given in physical order, sampled in `mode` (and reverse).
  ScatterDensity pdf(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const;

 protected:
  // Models are owned by their materials (or built for one hit), never deleted through this type.
  ~BsdfModel() = default;
};

}  // namespace kasha
