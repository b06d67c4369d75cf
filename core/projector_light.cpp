#include "core/projector_light.h"

#include <cmath>

namespace kasha {

namespace {

float tanHalf(float degrees) { return std::tan(0.5f * degrees * kPi / 180.0f); }

}  // namespace

ProjectorLight::ProjectorLight(Vec3 position, Vec3 lookAt, Vec3 up, float fovXDegrees, const RgbImage& image,
                               float scale, WavelengthRange range)
    : Light(Spectrum::constant(0.0f), scale, 0.0f),
      pos_(position),
      image_(image, lookAtFrame(position, lookAt, up), tanHalf(fovXDegrees),
             tanHalf(fovXDegrees) * float(image.height) / float(image.width)) {
  const std::vector<RgbIlluminant>& texels = image_.texels();
  spectrum_ = meanTexelSpectrum(texels, std::vector<float>(texels.size(), 1.0f), double(texels.size()), range);
  powerFactor_ = kPi * image_.planeArea();  // ∫I dω = π·scale·∫E dA over the plane z = 1
}

float ProjectorLight::emittedTowards(float lambda, const Vec3&, const Vec3& w) const {
  const std::optional<Vec2> uv = image_.directionToUv(w);
  if (!uv) return 0.0f;
  const float cosTheta = glm::dot(w, image_.frame().n);
  return kPi * scale_ * image_.texel(*uv)(lambda) / (cosTheta * cosTheta * cosTheta);
}

std::optional<LightSample> ProjectorLight::sampleLi(const Vec3& p, float lambda, Vec2) const {
  return sampleLightPoint(p, pos_, [&](const Vec3& w) { return emittedTowards(lambda, Vec3(0.0f), w); });
}

float ProjectorLight::Li(const LightSample& s, float lambda) const {
  return emittedTowards(lambda, Vec3(0.0f), -s.wi) / (s.dist * s.dist);
}

std::optional<EmissionSample> ProjectorLight::sampleEmission(float lambda, Vec2, Vec2 uDir) const {
  const std::optional<ProjectedImage::Sample> s = image_.sample(uDir);
  if (!s) return std::nullopt;
  EmissionSample es;
  es.p = pos_;
  es.w = s->w;
  es.Le = kPi * scale_ * image_.texel(s->uv)(lambda) / (s->cosTheta * s->cosTheta * s->cosTheta);
  es.pdfPos = 1.0f;
  es.pdfDir = s->pdf;
  es.deltaPos = true;
  return es;
}

float ProjectorLight::emitted(const EmissionSample& s, float lambda) const { return emittedTowards(lambda, s.n, s.w); }

void ProjectorLight::emissionPdfs(const Vec3&, const Vec3&, const Vec3& w, float& pdfPos, float& pdfDir) const {
  pdfPos = 1.0f;
  pdfDir = image_.pdf(w);
}

}  // namespace kasha
