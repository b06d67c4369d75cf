#include "core/image_input.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include "core/error.h"
#include "core/spectral_exr.h"

namespace kasha {

XyzImage readExrXyz(const std::string& path) {
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i dw = file.header().dataWindow();
    XyzImage img;
    img.width = dw.max.x - dw.min.x + 1;
    img.height = dw.max.y - dw.min.y + 1;
    for (const char* c : {"XYZ.X", "XYZ.Y", "XYZ.Z"})
      if (!file.header().channels().findChannel(c)) {
        if (hasEmissiveChannels(path)) return spectralToXyz(readSpectralExr(path));
        throw InputError(path, c, "missing channel (not a kasha render with an XYZ layer, nor a spectral image with S0.* channels)");
      }
    std::vector<float> ch[3];
    Imf::FrameBuffer fb;
    const char* names[3] = {"XYZ.X", "XYZ.Y", "XYZ.Z"};
    for (int c = 0; c < 3; ++c) {
      ch[c].resize(size_t(img.width) * img.height);
      char* base = reinterpret_cast<char*>(ch[c].data() - dw.min.x - size_t(dw.min.y) * img.width);
      fb.insert(names[c], Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * img.width));
    }
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    img.pixels.resize(ch[0].size());
    for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = Vec3(ch[0][i], ch[1][i], ch[2][i]);
    return img;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path, "", std::string("cannot read OpenEXR: ") + e.what());
  }
}

}  // namespace kasha
