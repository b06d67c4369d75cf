#pragma once
// Mitsuba 3 participating media as kasha media (docs/mitsuba-import.md "Media"; kasha's JSON:
// materials/medium_json.h). Mitsuba describes a medium by its extinction σ_t, its single-scattering
// albedo α and a factor `scale` (Mitsuba 3 docs: homogeneous; defaults σ_t = 1, α = 0.75,
// scale = 1); kasha by absorption and scattering, so
//   σ_a(λ) = σ_t(λ)·(1 − α(λ))·scale,   σ_s(λ) = σ_t(λ)·α(λ)·scale.
// The phase function is `isotropic` (kasha's g = 0, Mitsuba's default) or `hg` (g; Mitsuba's
// default 0.8). kasha's extension `fluorescent_homogeneous` adds <fluorophore> elements; a
// `heterogeneous` medium whose σ_t is a `gridvolume` becomes kasha's "heterogeneous" medium whose
// density file scales the coefficients (the JSON loader refuses it until heterogeneous transport
// exists).
#include <optional>
#include <string>
#include <vector>

#include "scene/mitsuba/scene_json.h"

namespace kasha::mitsuba {

// Translates a <medium> element into /media under a unique name (its id, else its label) and
// returns the name.
std::string addMedium(XmlImport& xml, pugi::xml_node medium, SceneJson& out);

// The medium `n` gives a shape or an endpoint (sensor, emitter): a nested <medium> (translated
// here) or a <ref> to a <medium id> declared before; nullopt if `n` is neither.
std::optional<std::string> mediumOf(XmlImport& xml, pugi::xml_node n, SceneJson& out);

// The medium an endpoint (a <sensor> or <emitter>) sits in: Mitsuba 3's endpoints take one nested
// <medium> or <ref> to one, under any name; nullopt if none. The endpoint's other <ref>s are
// appended to `otherRefs`.
std::optional<std::string> endpointMedium(Plugin& endpoint, SceneJson& out, std::vector<pugi::xml_node>& otherRefs);

}  // namespace kasha::mitsuba
