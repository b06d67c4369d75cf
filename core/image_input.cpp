#include "core/image_input.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>

#include <cmath>
#include <cstring>

#include "core/error.h"
#include "core/input_file.h"

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

// OpenEXR's input stream over bytes in memory.
class ExrInput::MemoryStream : public Imf::IStream {
 public:
  MemoryStream(const std::string& bytes, const std::string& name) : Imf::IStream(name.c_str()), bytes_(bytes) {}
  bool read(char c[], int n) override {
    if (n < 0 || uint64_t(n) > bytes_.size() - position_) throw std::runtime_error("unexpected end of file");
    std::memcpy(c, bytes_.data() + position_, size_t(n));
    position_ += uint64_t(n);
    return position_ < bytes_.size();
  }
  uint64_t tellg() override { return position_; }
  void seekg(uint64_t pos) override {
    if (pos > bytes_.size()) throw std::runtime_error("seek past the end of the file");
    position_ = pos;
  }

 private:
  const std::string& bytes_;
  uint64_t position_ = 0;
};

ExrInput::ExrInput(const std::string& path, const std::string& what)
    : bytes_(readInputFile(path, what, kMaxImageFileBytes)) {
  try {
    stream_ = std::make_unique<MemoryStream>(bytes_, path);
    file_ = std::make_unique<Imf::InputFile>(*stream_);
  } catch (const std::exception& e) {
    throw InputError(path, "", std::string("cannot read OpenEXR: ") + e.what());
  }
  const Imath::Box2i dw = file_->header().dataWindow();
  if (dw.max.x < dw.min.x || dw.max.y < dw.min.y) throw InputError(path, "", "OpenEXR data window is empty");
  width_ = uint64_t(int64_t(dw.max.x) - dw.min.x + 1);
  height_ = uint64_t(int64_t(dw.max.y) - dw.min.y + 1);
}

ExrInput::~ExrInput() = default;

std::unique_ptr<Imf::IStream> ExrInput::stream() const { return std::make_unique<MemoryStream>(bytes_, stream_->fileName()); }

XyzImage readExrXyz(const std::string& path, uint64_t memoryLimit) {
  ExrInput in(path, "image file");
  Imf::InputFile& file = in.file();
  for (const char* c : {"XYZ.X", "XYZ.Y", "XYZ.Z"})
    if (!file.header().channels().findChannel(c))
      throw InputError(path, c, "missing channel (not a kasha render with an XYZ layer)");
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
    for (size_t i = 0; i < img.pixels.size(); ++i) {
      img.pixels[i] = Vec3(ch[0][i], ch[1][i], ch[2][i]);
      if (!std::isfinite(ch[0][i]) || !std::isfinite(ch[1][i]) || !std::isfinite(ch[2][i]))
        throw InputError(path, "", "pixel (" + std::to_string(i % size_t(img.width)) + ", " +
                                       std::to_string(i / size_t(img.width)) + ") is not finite");
    }
    return img;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path, "", std::string("cannot read OpenEXR: ") + e.what());
  }
}

}  // namespace kasha
