#include "core/exr_input.h"

#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>

#include <cstring>
#include <stdexcept>

#include "core/error.h"
#include "core/input_file.h"

namespace kasha {

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

}  // namespace kasha
