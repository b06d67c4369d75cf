#include "scene/render_settings.h"

namespace kasha {

void checkProgressiveSettings(const ProgressiveSettings& p, const SettingFailure& fail) {
  if (p.photonsPerPass < 0) fail("photons_per_pass", "must not be negative (0: one per pixel)");
  if (!(p.radius >= 0.0f)) fail("radius", "must not be negative (0: from the scene)");
  // Consistency of the merges through the wavelength kernel (two dimensions in space, one in
  // wavelength) needs α > 1/3.
  if (!(p.alpha > 1.0f / 3.0f && p.alpha < 1.0f)) fail("alpha", "must be in (1/3, 1)");
  if (!(p.bandwidth >= 0.0f)) fail("bandwidth", "must not be negative (0: 1% of the wavelength range)");
  if (!(p.volumeRadius >= 0.0f)) fail("volume_radius", "must not be negative (0: from the scene)");
}

void checkBdptSettings(const BdptSettings& b, const SettingFailure& fail) {
  if (b.mollify && b.families != BdptFamilies::Own)
    fail("mollify", "mollifies the own family's connections: needs render/bdpt/families \"own\"");
  if (!(b.mollifyBandwidth >= 0.0f)) fail("mollify_bandwidth", "must not be negative (0: 2% of the wavelength range)");
  if (!(b.mollifyAlpha > 0.0f && b.mollifyAlpha < 1.0f)) fail("mollify_alpha", "must be in (0, 1)");
}

}  // namespace kasha
