#include "core/spectral_exr.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <algorithm>
#include <cmath>

#include "core/color.h"
#include "core/error.h"
#include "core/exr_input.h"
#include "core/memory_budget.h"
#include "core/exr_wavelength.h"

namespace kasha {
namespace {

// The wavelength of an "S0.<λ>" channel name; empty for any other channel.
std::optional<float> emissiveWavelength(const std::string& name) {
  if (name.rfind("S0.", 0) != 0) return std::nullopt;
  const std::string part = name.substr(3);
  if (part.find('.') != std::string::npos) return std::nullopt;
  return parseExrWavelength(part);
}

}  // namespace

std::string emissiveChannelName(float nm) { return "S0." + exrWavelengthName(nm); }

std::vector<std::pair<std::string, std::string>> spectralAttributes() {
  return {{"spectralLayoutVersion", "1.0"}, {"emissiveUnits", "W.m^-2.sr^-1"}};
}

std::vector<std::pair<std::string, std::vector<float>>> spectralChannels(const SpectralFilm& film) {
  const int w = film.width(), h = film.height(), n = film.bins().count;
  std::vector<std::pair<std::string, std::vector<float>>> out;
  out.reserve(size_t(n));
  for (int b = 0; b < n; ++b) {
    std::vector<float> img(size_t(w) * h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) img[size_t(y) * w + x] = film.value(x, y, b);
    out.emplace_back(emissiveChannelName(film.bins().centre(b)), std::move(img));
  }
  return out;
}

bool hasEmissiveChannels(ExrInput& in) {
  const Imf::ChannelList& channels = in.file().header().channels();
  for (auto it = channels.begin(); it != channels.end(); ++it)
    if (emissiveWavelength(it.name())) return true;
  return false;
}

SpectralImage readSpectralExr(const std::string& path, uint64_t memoryLimit) {
  ExrInput in(path, "image file");
  return readSpectralExr(in, path, memoryLimit);
}

SpectralImage readSpectralExr(ExrInput& in, const std::string& path, uint64_t memoryLimit) {
  Imf::InputFile& file = in.file();
  std::vector<std::pair<float, std::string>> channels;
  for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it)
    if (const std::optional<float> l = emissiveWavelength(it.name())) channels.emplace_back(*l, it.name());
  if (channels.empty())
    throw InputError(path, "", "no emissive channel S0.<wavelength> (Fichet et al. 2021 spectral layout)");
  std::sort(channels.begin(), channels.end());
  for (size_t k = 1; k < channels.size(); ++k)
    if (channels[k].first == channels[k - 1].first)
      throw InputError(path, channels[k].second, "same wavelength as channel " + channels[k - 1].second);
  const size_t n = channels.size();
  // A float per channel, and the XYZ pixels readExrXyz may integrate from them.
  requireImageMemory(path, in.width(), in.height(), saturatingMul(n, sizeof(float)) + sizeof(Vec3), memoryLimit);
  try {
    const Imath::Box2i dw = file.header().dataWindow();
    SpectralImage img;
    img.width = int(in.width());
    img.height = int(in.height());
    const size_t pixels = size_t(img.width) * size_t(img.height);
    img.values.assign(pixels * n, 0.0f);
    // Pixel-major interleaving straight from the file: channel k at offset k, stride n floats.
    Imf::FrameBuffer fb;
    for (size_t k = 0; k < n; ++k) {
      img.wavelengths.push_back(channels[k].first);
      char* base = reinterpret_cast<char*>(img.values.data() + k) -
                   (int64_t(dw.min.x) + int64_t(dw.min.y) * img.width) * int64_t(n * sizeof(float));
      fb.insert(channels[k].second, Imf::Slice(Imf::FLOAT, base, n * sizeof(float), n * sizeof(float) * size_t(img.width)));
    }
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    for (size_t i = 0; i < img.values.size(); ++i)
      if (!std::isfinite(img.values[i]))
        throw InputError(path, channels[i % n].second, pixelName(i / n, img.width) + " is not finite");
    return img;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path, "", std::string("cannot read OpenEXR: ") + e.what());
  }
}

ExrImage readExrImage(const std::string& path, uint64_t memoryLimit) {
  ExrInput in(path, "image file");
  ExrImage out;
  out.xyz = readExrXyz(in, path, memoryLimit);
  if (hasEmissiveChannels(in)) out.spectral = readSpectralExr(in, path, memoryLimit);
  return out;
}

XyzImage spectralToXyz(const SpectralImage& image) {
  const Observer& obs = Observer::cie1931();
  const std::vector<float>& c = image.wavelengths;
  const size_t n = c.size();
  std::vector<Vec3> weight(n);
  for (size_t k = 0; k < n; ++k) {
    const float below = k > 0 ? c[k] - c[k - 1] : (n > 1 ? c[1] - c[0] : 1.0f);
    const float above = k + 1 < n ? c[k + 1] - c[k] : below;
    const float lo = c[k] - 0.5f * below, hi = c[k] + 0.5f * above;
    weight[k] = Vec3(obs.xbar.integral(lo, hi), obs.ybar.integral(lo, hi), obs.zbar.integral(lo, hi)) / obs.yIntegral;
  }
  XyzImage xyz;
  xyz.width = image.width;
  xyz.height = image.height;
  xyz.pixels.resize(size_t(image.width) * image.height);
  for (size_t p = 0; p < xyz.pixels.size(); ++p) {
    Vec3 sum(0.0f);
    for (size_t k = 0; k < n; ++k) sum += weight[k] * image.values[p * n + k];
    xyz.pixels[p] = sum;
  }
  return xyz;
}

}  // namespace kasha
