#pragma once
// One image per BDPT strategy (`kasha render --strategy-images`, docs/bdpt-mis.md §7): the
// contributions of each (s, t) strategy, with their MIS weights and without, accumulated from
// the samples' StrategySample records. Paths with more scattering vertices than a chosen depth go
// into one image, "deeper", so that the weighted images always sum to the render.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/film.h"
#include "core/pixel_filter.h"
#include "integrators/bidirectional/mis_observer.h"
#include "integrators/integrator.h"

namespace kasha::bidir {

// File stem of a strategy's image: "s2_t3" (camera-only and shared family), "s2_t3_own" (own
// wavelength family), "s1_t2_light_vertex", "s2_t2_mollified", "merge_t3" (every merge at camera
// vertex t − 1, vcm and bpm).
std::string strategyName(int s, int t, uint8_t variant);

// Watches one camera sample's strategies (mis_observer.h) for the images: appends their records to
// `out` (SampleContext::strategies, merged into StrategyImages after each pass).
class StrategyLog final : public MisObserver {
 public:
  explicit StrategyLog(std::vector<StrategySample>& out) : out_(out) {}
  void onStrategy(const StrategySample& r) override { out_.push_back(r); }

 private:
  std::vector<StrategySample>& out_;
};

class StrategyImages {
 public:
  // Splats (t = 1) spread over the pixels `filter` reaches, as the film's.
  StrategyImages(int width, int height, int maxDepth, const PixelFilter& filter)
      : w_(width), h_(height), maxDepth_(maxDepth), filter_(filter) {}
  // Not thread-safe: the render loop merges records after each pass.
  void add(const StrategySample& r);
  void setSamplesPerPixel(int spp);
  // Writes <dir>/<name>.exr (and .png if asked) for every strategy that contributed; with
  // `unweighted` also <name>_unweighted.exr/.png. Returns the files written.
  std::vector<std::string> write(const std::string& dir, bool unweighted, bool png, float exposureStops) const;

  struct Images {
    Film weighted, unweighted;
    Images(int w, int h) : weighted(w, h), unweighted(w, h) {}
  };
  const std::map<std::string, std::unique_ptr<Images>>& images() const { return images_; }
  // An upper bound on the bytes the films may take (every strategy of every length up to the depth).
  static uint64_t bytesFor(int width, int height, int maxDepth);

 private:
  int w_, h_, maxDepth_;
  PixelFilter filter_;
  std::map<std::string, std::unique_ptr<Images>> images_;
};

}  // namespace kasha::bidir
