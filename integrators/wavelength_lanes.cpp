#include "integrators/wavelength_lanes.h"

#include <algorithm>

namespace kasha {

float laneStratum(float u, int k, int n) {
  const float x = u + float(k) / float(n);
  return std::min(x < 1.0f ? x : x - 1.0f, kBelowOne);
}

SampledLanes sampleLanes(const WavelengthDensity& density, float u, int n) {
  SampledLanes lanes;
  lanes.n = n;
  for (int k = 0; k < n; ++k) {
    const WavelengthSample ws = density.sample(laneStratum(u, k, n));
    lanes.lambda[k] = ws.lambda;
    lanes.pdf[k] = ws.pdf;
  }
  return lanes;
}

LaneEvent sampleLaneEvent(const Bsdf& bsdf, TransportMode mode, std::span<const float> known, int fresh, float u,
                          const WavelengthDensity* strategy, FluorescentLanes atFluorescence) {
  const int n = int(known.size());
  // The fluorescent lobe with the mean of the lanes' probabilities: symmetric in the lanes.
  float p[kMaxLanes];
  float pFluor = 0.0f;
  for (int j = 0; j < n; ++j) {
    p[j] = bsdf.has(BsdfFlags::Fluorescent) ? bsdf.fluorescenceProbability(mode, known[j]) : 0.0f;
    pFluor += p[j];
  }
  pFluor /= float(n);
  LaneEvent e;
  if (!(u < pFluor)) {
    if (!(pFluor < 1.0f)) return e;
    e.n = n;
    for (int j = 0; j < n; ++j) {
      e.lambda[j] = known[j];
      e.source[j] = j;
      e.scale[j] = 1.0f / (1.0f - pFluor);
      e.odds[j] = 1.0f;
    }
    return e;
  }
  // A fresh set of lanes at the strata of v; ended, lane k serves known lane k alone.
  e.lobe = SpectralLobe::Fluorescent;
  e.ended = atFluorescence == FluorescentLanes::End;
  e.n = e.ended ? n : fresh;
  for (int k = 0; k < e.n; ++k) {
    e.source[k] = e.ended ? k : kEveryLane;
    e.odds[k] = e.ended ? p[k] : 1.0f;
  }
  const float v = std::min(u / pFluor, kBelowOne);
  if (strategy) {
    // Through: N samples of one density serve each lane before (weight 1/(N·p)); ended: lane k
    // alone is an estimate for known lane k (weight 1/p).
    const float samples = e.ended ? 1.0f : float(e.n);
    for (int k = 0; k < e.n; ++k) {
      const WavelengthSample s = strategy->sample(laneStratum(v, k, e.n));
      e.lambda[k] = s.lambda;
      e.scale[k] = s.pdf > 0.0f ? 1.0f / (pFluor * samples * s.pdf) : 0.0f;
    }
    return e;
  }
  // The Bsdf's own density given lane m's wavelength, q_m = spectralPdf / P(λ_m). Ended: lane k is
  // drawn from q_k (weight 1/(P̄·q_k); none if lane k cannot fluoresce).
  if (e.ended) {
    for (int k = 0; k < e.n; ++k) {
      e.lambda[k] = known[k];
      e.scale[k] = 0.0f;
      if (!(p[k] > 0.0f)) continue;
      const SpectralChoice c = bsdf.sampleSpectral(mode, known[k], laneStratum(v, k, e.n) * p[k]);
      e.lambda[k] = c.lambda;
      if (c.lobe == SpectralLobe::Fluorescent && c.pdf > 0.0f) e.scale[k] = p[k] / (pFluor * c.pdf);
    }
    return e;
  }
  // Through, for the lanes that can fluoresce: lane k is drawn from component k mod V, and the
  // multi-sample balance heuristic (Veach97 §9.2.2) divides it by Σ_m n_m·q_m(λ_k).
  int valid[kMaxLanes], count[kMaxLanes];
  int nValid = 0;
  for (int j = 0; j < n; ++j)
    if (p[j] > 0.0f) valid[nValid++] = j;
  for (int m = 0; m < nValid; ++m) count[m] = e.n / nValid + (m < e.n % nValid ? 1 : 0);
  for (int k = 0; k < e.n; ++k) {
    const int j = valid[k % nValid];
    const SpectralChoice c = bsdf.sampleSpectral(mode, known[j], laneStratum(v, k, e.n) * p[j]);
    e.lambda[k] = c.lambda;
    e.scale[k] = 0.0f;
    if (c.lobe != SpectralLobe::Fluorescent || !(c.pdf > 0.0f)) continue;
    float density = 0.0f;
    if (bsdf.has(BsdfFlags::FactorisedFluorescence))  // every q_m is the same q (Kasha's rule)
      density = float(e.n) * bsdf.spectralPdf(mode, known[j], c.lambda, c.lobe) / p[j];
    else
      for (int m = 0; m < nValid; ++m)
        density += float(count[m]) * bsdf.spectralPdf(mode, known[valid[m]], c.lambda, c.lobe) / p[valid[m]];
    e.scale[k] = density > 0.0f ? 1.0f / (pFluor * density) : 0.0f;
  }
  return e;
}

bool lanesEndAt(const LaneEvent& e, const Bsdf& bsdf) {
  return e.ended || (e.lobe == SpectralLobe::Elastic && bsdf.has(BsdfFlags::WavelengthDependentDirection));
}

void keepOneLane(LaneEvent& e, float u) {
  if (e.n <= 1) return;
  float total = 0.0f;
  for (int j = 0; j < e.n; ++j) total += e.odds[j];
  // The first lane whose cumulative odds pass u·total; rounding: the last one with odds.
  int j = 0;
  for (float acc = e.odds[0]; j + 1 < e.n && !(u * total < acc);) acc += e.odds[++j];
  while (j > 0 && !(e.odds[j] > 0.0f)) --j;
  e.lambda[0] = e.lambda[j];
  e.source[0] = e.source[j];
  e.scale[0] = e.odds[j] > 0.0f ? e.scale[j] * (total / e.odds[j]) : 0.0f;
  e.odds[0] = 1.0f;
  e.n = 1;
}

}  // namespace kasha
