#pragma once
// Next-event estimation for the wavelength lanes of a camera path (Radiance mode), shared by the
// path tracer and photon mapping (docs/wavelength-sampling.md "Hero wavelengths",
// docs/photon-mapping.md §3). One light is chosen for the lanes after the vertex's spectral event
// (LaneLightChoice: after the lanes' weights and the lights' power at them), one point on it serves
// every lane (a light's geometry does not depend on λ), and lane k of the event adds
// laneWeight(k)·|cos θ_i|·L_i(λ_k)·w/(P(l)·p_light), the shadow ray traced only if some lane gets
// light. For a fluorescent event the excitation lanes λ_k were drawn as the path tracer draws them
// (sampleLaneEvent: Jung18 eq. 7's P_c, then λ_i from the fluorescence strategy or the material).
#include <cmath>
#include <span>
#include <stdexcept>
#include <string>

#include "core/sampling.h"
#include "scene/render_settings.h"
#include "scene/wavelength_strategy.h"
#include "integrators/lane_light_choice.h"
#include "integrators/medium_transport.h"
#include "integrators/wavelength_lanes.h"

namespace kasha {

// Checks the settings that lanes with this next-event estimation need: nee_sampling "event" (the
// lanes' light sample serves the event's own excitation lanes) and lanes in [minLanes, kMaxLanes].
// `who` names the integrator in the messages ("hero wavelengths", "ppm"). Throws
// WavelengthStrategyError or std::invalid_argument.
inline void requireLaneSettings(const RenderSettings& s, int lanes, int minLanes, const std::string& who) {
  if (!s.wavelengths.nee.uses(WavelengthSpec::Kind::Event))
    throw WavelengthStrategyError(WavelengthSite::Nee, "nee_sampling '" + s.wavelengths.nee.text +
                                                           "' is not supported with " + who + " (leave it at 'event')");
  if (lanes < minLanes || lanes > kMaxLanes)
    throw std::invalid_argument(who + ": " + std::to_string(lanes) + " wavelength lanes is outside [" +
                                std::to_string(minLanes) + ", " + std::to_string(kMaxLanes) + "]");
}

// How next-event estimation is weighted against hitting the light by direction sampling.
enum class NeeWeight {
  PowerHeuristic,  // the path also samples the direction from lane 0's wavelengths and counts emission it hits
  Alone,           // the path never reaches a light through a non-specular direction: weight 1
};

// The wavelength densities that next-event estimation's MIS weight compares where it drew a λ_i
// of its own instead of the event's (the path tracer's nee_sampling, one lane): the light sample's
// P_c·p_nee(λ_i) and the event's P_c·p_event(λ_i) (docs/wavelength-sampling.md, "Fluorescent event
// override"). Both 1 where the light sample serves the event's own lanes: the densities cancel.
struct NeeSpectralPdfs {
  float nee = 1.0f, event = 1.0f;
};

// The contribution of one light sample to every lane of event `e` at the non-specular vertex
// `hit` (outgoing direction wo in the Bsdf's frame; a surface hit, or a point in a medium with
// ng = 0, `where` saying which, with the transmittance of the media on the shadow ray); `before[j]` is lane j's throughput before
// the event at the known wavelength known[j], `lights` the light choice for the event's lanes
// (a LaneLightChoice reset with e.lambda, or a OneLaneLightChoice), lambdaOut0 the outgoing
// wavelength the direction sampling of the event's lane 0 uses (for the power heuristic), `spectral`
// the wavelength densities the power heuristic compares besides the directions'. uLight chooses the
// light, uPos the point on it. Returns zero at a purely specular vertex. T is the lanes' throughput
// type.
template <class T, class LightChoice>
T laneNextEvent(const Scene& scene, const Hit& hit, VertexMedium where, const Bsdf& bsdf, const Vec3& wo,
                std::span<const float> known,
                const T* before, const LaneEvent& e, const LightChoice& lights, float lambdaOut0, float uLight,
                Vec2 uPos, NeeWeight weighting, RayCounter& counter, NeeSpectralPdfs spectral = {}) {
  T sum = before[0] * 0.0f;
  if (e.n == 0 || bsdf.has(BsdfFlags::DeltaDirection)) return sum;
  const auto [li, pSelect] = lights.select(uLight);
  if (!(pSelect > 0.0f)) return sum;
  const std::optional<LightSample> ls = scene.lights[li]->sampleLi(hit.p, e.lambda[0], uPos);
  if (!ls || !(ls->pdf > 0.0f)) return sum;
  const Vec3 wi = bsdf.toLocal(ls->wi);
  const float lightPdf = pSelect * ls->pdf;
  // Each lane's weight and radiance first: the shadow ray only where they can change the estimate,
  // the MIS weight (a direction density) only where the light is seen.
  T weight[kMaxLanes];
  float Li[kMaxLanes];
  bool any = false;
  for (int k = 0; k < e.n; ++k) {
    // The light's geometry does not depend on λ: the same point at every lane's wavelength.
    Li[k] = k == 0 ? ls->Li : scene.lights[li]->Li(*ls, e.lambda[k]);
    if (!(Li[k] > 0.0f)) continue;
    weight[k] = laneWeight(bsdf, TransportMode::Radiance, known, before, e, k, wi, wo);
    any = any || !(weight[k] == sum);
  }
  float tr[kMaxLanes];
  if (!any || bsdf.cosineFactor(wi) == 0.0f ||
      !lightTransmittance(scene, hit, where, *ls, {e.lambda, size_t(e.n)}, tr, counter))
    return sum;
  const float w =
      ls->delta || weighting == NeeWeight::Alone
          ? 1.0f
          : powerHeuristic(
                lightPdf * spectral.nee,
                bsdf.directionPdf({TransportMode::Radiance, e.lobe, e.lambda[0], lambdaOut0}, wo, wi) * spectral.event);
  for (int k = 0; k < e.n; ++k)
    if (Li[k] > 0.0f) sum += weight[k] * (bsdf.cosineFactor(wi) * tr[k] * Li[k] * w / lightPdf);
  return sum;
}

}  // namespace kasha
