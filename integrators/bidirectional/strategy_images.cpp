#include "integrators/bidirectional/strategy_images.h"

#include <algorithm>
#include <cmath>

#include "core/image_output.h"
#include "core/memory_budget.h"
#include "integrators/bidirectional/mis.h"

namespace kasha::bidir {

std::string strategyName(int s, int t, uint8_t variant) {
  // Every merge at camera vertex t − 1 in one image, whichever light vertex it used.
  if (isMerge(Variant(variant))) return "merge_t" + std::to_string(t);
  std::string name = "s" + std::to_string(s) + "_t" + std::to_string(t);
  if (variant == uint8_t(Variant::kLightVertex)) name += "_light_vertex";
  if (variant == uint8_t(Variant::kMollified)) name += "_mollified";
  if (variant == uint8_t(Variant::kOwn)) name += "_own";
  return name;
}

void StrategyImages::add(const StrategySample& r) {
  if (!std::isfinite(r.pixel.x) || !std::isfinite(r.pixel.y)) return;  // counted by the main film
  const std::string name = r.s + r.t - 2 > maxDepth_ ? "deeper" : strategyName(r.s, r.t, r.variant);
  std::unique_ptr<Images>& img = images_[name];
  if (!img) img = std::make_unique<Images>(w_, h_);
  // t ≥ 2 reports the camera sample's pixel (its corner), t = 1 a splat's film position.
  const auto add = [&](int x, int y, float weight) {
    img->weighted.addSplat(x, y, r.weighted * weight);
    img->unweighted.addSplat(x, y, r.unweighted * weight);
  };
  if (r.t == 1) filter_.splat(r.pixel, w_, h_, add);
  else PixelFilter().splat(r.pixel, w_, h_, add);
}

void StrategyImages::setSamplesPerPixel(int spp) {
  for (auto& [name, img] : images_) {
    img->weighted.setSamplesPerPixel(spp);
    img->unweighted.setSamplesPerPixel(spp);
  }
}

std::vector<std::string> StrategyImages::write(const std::string& dir, bool unweighted, bool png, float exposure) const {
  std::vector<std::string> files;
  auto put = [&](const Film& film, const std::string& stem) {
    files.push_back(dir + "/" + stem + ".exr");
    writeExr(film, files.back());
    if (!png) return;
    files.push_back(dir + "/" + stem + ".png");
    writePng(film, files.back(), exposure);
  };
  for (const auto& [name, img] : images_) {
    put(img->weighted, name);
    if (unweighted && name != "deeper") put(img->unweighted, name + "_unweighted");
  }
  return files;
}

uint64_t StrategyImages::bytesFor(int width, int height, int maxDepth) {
  // Paths of k = 1 … K segments (K = maxDepth + 1): k + 1 standard strategies each, at most k
  // of the own-wavelength family, one light-vertex variant and k − 2 mollified ones
  // (s = 2 … k − 1); the merges at each camera vertex t − 1 = 1 … K − 1; and "deeper".
  const uint64_t K = uint64_t(std::max(0, maxDepth)) + 1;
  const uint64_t strategies = K * (K + 3) / 2 + K * (K + 1) / 2 + K + (K - 1) * (K - 2) / 2 + (K - 1) + 1;
  return saturatingMul(saturatingMul(strategies, 2), Film::bytesFor(width, height));
}

}  // namespace kasha::bidir
