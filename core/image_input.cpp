#include "core/image_input.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <cmath>

#include "core/error.h"
#include "core/exr_input.h"
#include "core/spectral_exr.h"

namespace kasha {

void requireImageMemory(const std::string& path, uint64_t width, uint64_t height, uint64_t bytesPerPixel,
                        uint64_t limit) {
  try {
    requireMemory(saturatingMul(saturatingMul(width, height), bytesPerPixel),
                  "decoding its " + std::to_string(width) + "x" + std::to_string(height) + " pixels", limit);
  } catch (const MemoryLimitError& e) {
    throw InputError(path, "", e.what());
  }
}

std::string pixelName(size_t index, int width) {
  return "pixel (" + std::to_string(index % size_t(width)) + ", " + std::to_string(index / size_t(width)) + ")";
}

void requireFinitePixels(const XyzImage& image, const std::string& where, const std::string& problem) {
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const Vec3& p = image.pixels[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw InputError(where, "", pixelName(i, image.width) + " " + problem);
  }
}

XyzImage readExrXyz(const std::string& path, uint64_t memoryLimit) {
  ExrInput in(path, "image file");
  return readExrXyz(in, path, memoryLimit);
}

XyzImage readExrXyz(ExrInput& in, const std::string& path, uint64_t memoryLimit) {
  Imf::InputFile& file = in.file();
  for (const char* c : {"XYZ.X", "XYZ.Y", "XYZ.Z"})
    if (!file.header().channels().findChannel(c)) {
      if (hasEmissiveChannels(in)) {
        XyzImage img = spectralToXyz(readSpectralExr(in, path, memoryLimit));
        requireFinitePixels(img, path, "integrates to a non-finite XYZ");  // finite values may still sum past FLT_MAX
        return img;
      }
      throw InputError(path, c, "missing channel (not a kasha render with an XYZ layer, nor a spectral image with S0.* channels)");
    }
  // Three float channels and the XYZ pixels made of them.
  requireImageMemory(path, in.width(), in.height(), 3 * sizeof(float) + sizeof(Vec3), memoryLimit);
  try {
    const Imath::Box2i dw = file.header().dataWindow();
    XyzImage img;
    img.width = int(in.width());
    img.height = int(in.height());
    std::vector<float> ch[3];
    Imf::FrameBuffer fb;
    const char* names[3] = {"XYZ.X", "XYZ.Y", "XYZ.Z"};
    for (int c = 0; c < 3; ++c) {
      ch[c].resize(size_t(img.width) * img.height);
      char* base = reinterpret_cast<char*>(ch[c].data()) -
                   (int64_t(dw.min.x) + int64_t(dw.min.y) * img.width) * int64_t(sizeof(float));
      fb.insert(names[c], Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * img.width));
    }
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    img.pixels.resize(ch[0].size());
    for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = Vec3(ch[0][i], ch[1][i], ch[2][i]);
    requireFinitePixels(img, path);
    return img;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path, "", std::string("cannot read OpenEXR: ") + e.what());
  }
}

}  // namespace kasha
