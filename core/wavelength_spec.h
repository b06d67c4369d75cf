#pragma once
// The text form of a wavelength sampling strategy (docs/wavelength-sampling.md), as given on the
// command line and in a scene's render settings:
//
//   spec      := component | combination ":" component ("," component)*
//   combination := "mix"        one-sample MIS, balance heuristic (= sampling the mixture)
//                | "os-power"   one-sample MIS, power heuristic (β = 2)
//                | "ms-balance" multi-sample MIS, one sample per component, balance heuristic
//                | "ms-power"   multi-sample MIS, one sample per component, power heuristic
//   component := kind ["=" w_F] ["@" weight]   (w_F only for yamamoto; weight only in a combination)
//   kind      := uniform | cmf | light | absorption | emission | yamamoto | material | event
#include <string>
#include <vector>

namespace kasha {

struct WavelengthSpec {
  // Material: the material samples the fluorescent event itself (fluorescence_sampling only).
  // Event: next-event estimation reuses the wavelength the event drew (nee_sampling only).
  enum class Kind { Uniform, ColorMatching, LightPower, Absorption, Emission, Yamamoto, Material, Event };
  enum class Combination { Single, Mixture, OneSamplePower, MultiBalance, MultiPower };
  struct Component {
    Kind kind = Kind::Uniform;
    float weight = 1.0f;       // selection weight in a one-sample combination (normalised)
    float yamamotoWF = -1.0f;  // Yamamoto's w_F in [0, 1]; < 0: 1/2
  };
  Combination combination = Combination::Single;
  std::vector<Component> components;
  std::string text;  // as given

  // True when the strategy draws from one density p(λ) (single or one-sample balance), so that
  // p(λ) can enter other MIS weights.
  bool isDensity() const { return combination == Combination::Single || combination == Combination::Mixture; }
  bool uses(Kind k) const;
};

// Throws std::invalid_argument naming the offending part.
WavelengthSpec parseWavelengthSpec(const std::string& text);
const char* toString(WavelengthSpec::Kind k);

}  // namespace kasha
