#include "scene/wavelength_strategy.h"

#include <algorithm>
#include <stdexcept>

#include "core/color.h"

namespace kasha {
namespace {

using Kind = WavelengthSpec::Kind;
using Combination = WavelengthSpec::Combination;

std::shared_ptr<const SpectralDistribution> distribution(const Spectrum& s, WavelengthRange range) {
  return std::make_shared<SpectralDistribution>(s, range);
}

WavelengthDensity single(const Spectrum& s, WavelengthRange range, const char* what) {
  auto dist = distribution(s, range);
  if (!(dist->integral() > 0.0f))
    throw std::invalid_argument(std::string(what) + " is zero over " + std::to_string(int(range.min)) + "–" +
                                std::to_string(int(range.max)) + " nm");
  WavelengthDensity d;
  d.add(std::move(dist), 1.0f);
  return d;
}

WavelengthDensity component(const WavelengthSpec::Component& c, const WavelengthSources& src, WavelengthSite site,
                            size_t material) {
  const bool event = site == WavelengthSite::Fluorescence || site == WavelengthSite::Nee;
  const WavelengthSources::Fluorophore* own = event ? src.fluorophoreOf(material) : nullptr;
  const WavelengthRange range = src.rangeOf(site);
  switch (c.kind) {
    case Kind::Uniform:
      return single(Spectrum::constant(1.0f), range, "uniform");
    case Kind::ColorMatching: {
      WavelengthDensity d;
      d.add(src.colorMatching, 1.0f);
      return d;
    }
    case Kind::LightPower:
      return single(src.lightPower, range, "the lights' power");
    case Kind::Absorption:  // at a fluorescent event: the vertex's own absorption
      return own ? single(own->spectra.absorbed, range, "the absorption") : yamamotoFluorophoreDensity(src, true, range);
    case Kind::Emission:
      return yamamotoFluorophoreDensity(src, false, range);
    case Kind::Yamamoto: {
      // p_FL = w_F·p_F + w_L·p_L, w_L = 1 − w_F. p_F follows the wavelength being drawn: what the
      // fluorophores emit at the sensor, what they absorb for an excitation wavelength.
      const float wF = c.yamamotoWF < 0.0f ? 0.5f : c.yamamotoWF;
      WavelengthDensity d;
      if (wF > 0.0f) {
        if (own) d.add(single(own->spectra.absorbed, range, "the absorption"), wF);
        else d.add(yamamotoFluorophoreDensity(src, site != WavelengthSite::Sensor, range), wF);
      }
      if (wF < 1.0f) d.add(single(src.lightPower, range, "the lights' power"), 1.0f - wF);
      return d;
    }
    case Kind::Material:
      throw std::invalid_argument("'material' applies only to fluorescent events (fluorescence_sampling)");
    case Kind::Event:
      break;
  }
  throw std::invalid_argument("'event' applies only to next-event estimation (nee_sampling)");
}

}  // namespace

const char* toString(WavelengthSite s) {
  return s == WavelengthSite::Sensor         ? "sensor"
         : s == WavelengthSite::Fluorescence ? "fluorescence"
         : s == WavelengthSite::Nee          ? "next-event"
                                             : "light";
}

const char* settingName(WavelengthSite s) {
  return s == WavelengthSite::Sensor         ? "sensor_sampling"
         : s == WavelengthSite::Fluorescence ? "fluorescence_sampling"
         : s == WavelengthSite::Nee          ? "nee_sampling"
                                             : "light_sampling";
}

WavelengthSources::WavelengthSources(const Scene& scene) : range(scene.range) {
  // The observer is zero outside 360–830 nm.
  seen = {std::max(range.min, 360.0f), std::min(range.max, 830.0f)};
  const Observer& o = Observer::cie1931();
  colorMatching = distribution(Spectrum::weightedSum({{1.0f, &o.xbar}, {1.0f, &o.ybar}, {1.0f, &o.zbar}}), seen);
  std::vector<std::pair<float, const Spectrum*>> light, all;
  for (const auto& l : scene.lights) light.emplace_back(l->powerFactor() * l->scale(), &l->spectrum());
  lightPower = Spectrum::weightedSum(light);
  for (size_t m = 0; m < scene.materials.size(); ++m) {
    std::optional<FluorophoreSpectra> f = scene.materials[m]->fluorophore();
    if (!f) {
      if (has(scene.materials[m]->flags(), BsdfFlags::Fluorescent))
        throw std::logic_error("material " + scene.materialNames.at(m) + " fluoresces but gives no fluorophore spectra");
      continue;
    }
    Fluorophore fl{m, std::move(*f), 0.0f};
    for (const Shape& s : scene.shapes)
      if (s.material == m) fl.area += s.area;
    fluorophores.push_back(std::move(fl));
  }
  all.emplace_back(1.0f, &lightPower);
  for (const Fluorophore& f : fluorophores) all.emplace_back(1.0f, &f.spectra.reemitted);
  reachable = Spectrum::weightedSum(all);
}

const WavelengthSources::Fluorophore* WavelengthSources::fluorophoreOf(size_t material) const {
  for (const Fluorophore& f : fluorophores)
    if (f.material == material) return &f;
  return nullptr;
}

std::vector<float> yamamotoFluorophoreWeights(const std::vector<float>& areas, const std::vector<float>& integrals) {
  std::vector<float> w(areas.size());
  float total = 0.0f;
  for (size_t t = 0; t < w.size(); ++t) total += w[t] = areas[t] * integrals[t];  // A_t·k_Ft
  for (float& x : w) x = total > 0.0f ? x / total : 0.0f;
  return w;
}

WavelengthDensity yamamotoFluorophoreDensity(const WavelengthSources& src, bool absorbed, WavelengthRange range) {
  if (src.fluorophores.empty()) throw std::invalid_argument("the scene has no fluorescent material");
  std::vector<float> areas, integrals;
  std::vector<std::shared_ptr<const SpectralDistribution>> dists;
  for (const auto& f : src.fluorophores) {
    dists.push_back(distribution(absorbed ? f.spectra.absorbed : f.spectra.reemitted, range));
    areas.push_back(f.area);
    integrals.push_back(dists.back()->integral());  // k_Ft
  }
  const std::vector<float> w = yamamotoFluorophoreWeights(areas, integrals);
  WavelengthDensity d;
  for (size_t t = 0; t < w.size(); ++t)
    if (w[t] > 0.0f) d.add(dists[t], w[t]);
  if (d.empty())
    throw std::invalid_argument(std::string("the fluorophores ") + (absorbed ? "absorb" : "emit") + " nothing over " +
                                std::to_string(int(range.min)) + "–" + std::to_string(int(range.max)) + " nm");
  return d;
}

WavelengthStrategy::WavelengthStrategy(const WavelengthSpec& spec, const WavelengthSources& src, WavelengthSite site,
                                       size_t material)
    : spec_(spec) {
  const std::string name = spec.text;
  const bool multi = spec.combination == Combination::MultiBalance || spec.combination == Combination::MultiPower;
  float total = 0.0f;
  for (const auto& c : spec.components) {
    if (multi && c.weight != 1.0f)
      throw WavelengthStrategyError(site, "wavelength strategy '" + name + "': multi-sample MIS takes one sample per "
                                  "component, so weights '@' do not apply");
    try {
      parts_.push_back(component(c, src, site, material));
    } catch (const std::invalid_argument& e) {
      throw WavelengthStrategyError(site, "wavelength strategy '" + name + "': " + e.what());
    }
    c_.push_back(c.weight);
    total += c.weight;
  }
  for (size_t k = 0; k < parts_.size(); ++k) {
    c_[k] /= total;
    mixture_.add(parts_[k], c_[k]);
  }
  // Unbiasedness: the density (every component's, for multi-sample MIS, since the weights
  // partition unity only where some component samples) must be positive wherever the integrand
  // can be: where light reaches the observer, where the vertex's fluorophore absorbs light that
  // exists, or where a light emits.
  const Observer& o = Observer::cie1931();
  const Spectrum& reach = src.reachable;
  const WavelengthSources::Fluorophore* own = src.fluorophoreOf(material);
  std::function<float(float)> target;
  if (site == WavelengthSite::Sensor)
    target = [&](float l) { return (o.xbar(l) + o.ybar(l) + o.zbar(l)) * reach(l); };
  else if (site == WavelengthSite::Fluorescence || site == WavelengthSite::Nee)
    target = [&](float l) { return own ? own->spectra.absorbed(l) * reach(l) : 0.0f; };
  else
    target = [&](float l) { return src.lightPower(l); };
  const float miss = mixture_.firstUncovered(target, src.rangeOf(site));
  if (miss >= 0.0f)
    throw WavelengthStrategyError(site, "wavelength strategy '" + name + "' at the " + toString(site) +
                                " site has density 0 at " + std::to_string(int(miss)) +
                                " nm where the image needs light: it would be biased (combine it, e.g. mix:" + name +
                                ",uniform)");
}

int WavelengthStrategy::samplesPerEstimate() const {
  const bool multi = spec_.combination == Combination::MultiBalance || spec_.combination == Combination::MultiPower;
  return multi ? int(parts_.size()) : 1;
}

WavelengthStrategy::Draw WavelengthStrategy::draw(int i, float u) const {
  switch (spec_.combination) {
    case Combination::Single:
    case Combination::Mixture: {
      const WavelengthSample s = mixture_.sample(u);
      return s.pdf > 0.0f ? Draw{s.lambda, 1.0f / s.pdf} : Draw{};
    }
    case Combination::OneSamplePower: {
      // Veach97 eq. 9.15 with the power heuristic: choose k with c_k, λ ~ p_k, and weight
      // w_k/(c_k·p_k) with w_k = (c_k p_k)² / Σ_j (c_j p_j)², i.e. c_k·p_k / Σ_j (c_j p_j)².
      float acc = 0.0f;
      size_t k = 0;
      for (; k + 1 < parts_.size() && u >= acc + c_[k]; ++k) acc += c_[k];
      const float v = std::clamp((u - acc) / c_[k], 0.0f, 0x1.fffffep-1f);
      const WavelengthSample s = parts_[k].sample(v);
      if (s.pdf <= 0.0f) return {};
      float sum2 = 0.0f;
      for (size_t j = 0; j < parts_.size(); ++j) sum2 += sqr(c_[j] * parts_[j].pdf(s.lambda));
      return {s.lambda, c_[k] * s.pdf / sum2};
    }
    case Combination::MultiBalance:
    case Combination::MultiPower: {
      // Veach97 eq. 9.13 with one sample per strategy: w_i/p_i with w_i = p_i^β / Σ_j p_j^β.
      const WavelengthSample s = parts_[size_t(i)].sample(u);
      if (s.pdf <= 0.0f) return {};
      const bool power = spec_.combination == Combination::MultiPower;
      float sum = 0.0f;
      for (const WavelengthDensity& p : parts_) sum += power ? sqr(p.pdf(s.lambda)) : p.pdf(s.lambda);
      return {s.lambda, (power ? s.pdf : 1.0f) / sum};
    }
  }
  return {};
}

void requireDensity(const WavelengthSpec& spec, WavelengthSite site, const std::string& where) {
  if (!spec.isDensity())
    throw WavelengthStrategyError(site, "wavelength strategy '" + spec.text + "' is not supported " + where +
                                ": it needs one density (a single strategy or mix:…)");
}

}  // namespace kasha
