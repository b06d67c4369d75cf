#include "materials/textured_jung.h"

#include <array>
#include <map>
#include <stdexcept>

namespace kasha {
TexturedJung::TexturedJung(JungParams base, JungTextures tex, WavelengthRange range) {
  if (std::string m = checkJungParams(base, range); !m.empty()) throw std::invalid_argument(m);
  const std::array<std::pair<const char*, const std::shared_ptr<const ImageTexture>*>, 3> fields = {
      {{"reflectance_texture", &tex.reflectance}, {"c_texture", &tex.c}, {"Q_texture", &tex.q}}};
  const char* gridField = nullptr;
  for (const auto& [name, t] : fields) {
    if (!*t) continue;
    if (!grid_) {
      grid_ = *t;
      gridField = name;
    } else if ((*t)->width() != grid_->width() || (*t)->height() != grid_->height()) {
      throw std::invalid_argument(std::string(name) + ": " + std::to_string((*t)->width()) + "×" +
                                  std::to_string((*t)->height()) + " pixels, but " + gridField + " has " +
                                  std::to_string(grid_->width()) + "×" + std::to_string(grid_->height()) +
                                  " (the textures of one material must have the same size)");
    }
  }
  if (!grid_) throw std::invalid_argument("c_texture: a textured material needs at least one texture");
  const size_t n = size_t(grid_->width()) * size_t(grid_->height());
  std::map<std::array<float, 3>, uint32_t> entries;
  index_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const std::array<float, 3> key = {tex.reflectance ? tex.reflectance->texel(i) : 1.0f, tex.c ? tex.c->texel(i) : 1.0f,
                                      tex.q ? tex.q->texel(i) : 1.0f};
    auto [it, added] = entries.emplace(key, uint32_t(palette_.size()));
    if (added) {
      if (palette_.size() == kMaxPalette)
        throw std::invalid_argument(std::string(gridField) + ": more than " + std::to_string(kMaxPalette) +
                                    " distinct combinations of texture values (quantise the images)");
      JungParams p = base;
      p.reflectance = base.reflectance.scaled(key[0]);
      p.concentration = base.concentration * key[1];
      p.energyRatio = base.energyRatio * key[2];
      palette_.push_back(std::make_unique<JungBbrrdf>(std::move(p), range));
    }
    index_[i] = it->second;
  }
  // Flags and the fluorophore: union and texel-area mean over the entries.
  std::vector<float> texels(palette_.size(), 0.0f);
  for (uint32_t e : index_) texels[e] += 1.0f / float(n);
  std::vector<FluorophoreSpectra> spectra;
  std::vector<float> weights;
  for (size_t e = 0; e < palette_.size(); ++e) {
    flags_ = flags_ | palette_[e]->flags();
    if (auto f = palette_[e]->fluorophore()) {
      spectra.push_back(std::move(*f));
      weights.push_back(texels[e]);
    }
  }
  if (spectra.empty()) return;
  std::vector<std::pair<float, const Spectrum*>> absorbed, reemitted;
  for (size_t k = 0; k < spectra.size(); ++k) {
    absorbed.emplace_back(weights[k], &spectra[k].absorbed);
    reemitted.emplace_back(weights[k], &spectra[k].reemitted);
  }
  fluorophore_ = FluorophoreSpectra{Spectrum::weightedSum(absorbed), Spectrum::weightedSum(reemitted)};
}

}  // namespace kasha
