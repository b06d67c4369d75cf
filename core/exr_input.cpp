#include "core/exr_input.h"

#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>

#include <algorithm>
#include <cstring>
#include <map>
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

namespace {

// OpenEXR allocates header attributes at sizes the file declares before it reads them (a 400-byte
// file may claim a 2 GB string, preview or unknown attribute), and reads known types by their
// own structure whatever size is declared. So the headers are walked first, every attribute must
// take exactly the bytes it declares (what any writer produces), and no declared size may exceed
// the bytes that follow. Layout (OpenEXR file layout, "Header"): magic 20000630, a version word
// (bit 12: multi-part), then per header attributes name\0 type\0 int32 size and the value, ended
// by an empty name; a multi-part file ends its headers with an empty one.
class AttributeWalk {
 public:
  AttributeWalk(const std::string& bytes, const std::string& path) : b_(bytes), path_(path) {}

  void run() {
    if (b_.size() < 8 || b_.compare(0, 4, "\x76\x2f\x31\x01") != 0) return;  // OpenEXR refuses it
    const bool multipart = (uint8_t(b_[5]) & 0x10) != 0;
    pos_ = 8;
    while (true) {
      const std::string name = cString("attribute name");
      if (name.empty()) {  // end of a header
        if (!multipart || byte() == 0) return;
        continue;
      }
      const std::string type = cString("attribute type");
      const int32_t size = int32(name);
      if (size < 0 || uint64_t(size) > b_.size() - pos_)
        fail(name, "declares " + std::to_string(size) + " bytes, more than the file holds");
      const size_t end = pos_ + size_t(size);
      value(name, type, end);
      if (pos_ != end) fail(name, "of type " + type + " does not fill the " + std::to_string(size) + " bytes it declares");
    }
  }

 private:
  [[noreturn]] void fail(const std::string& name, const std::string& why) const {
    throw InputError(path_, "", "cannot read OpenEXR: header attribute '" + name + "' " + why);
  }
  uint8_t byte() {
    if (pos_ >= b_.size()) throw InputError(path_, "", "cannot read OpenEXR: the header is truncated");
    return uint8_t(b_[pos_++]);
  }
  std::string cString(const char* what) {
    std::string out;
    for (uint8_t c = byte(); c != 0; c = byte()) {
      out += char(c);
      if (out.size() > 255) throw InputError(path_, "", std::string("cannot read OpenEXR: ") + what + " is too long");
    }
    return out;
  }
  int32_t int32(const std::string& name) {
    if (b_.size() - std::min(pos_, b_.size()) < 4) fail(name, "is truncated");
    uint32_t v = 0;
    for (int k = 0; k < 4; ++k) v |= uint32_t(uint8_t(b_[pos_ + size_t(k)])) << (8 * k);
    pos_ += 4;
    return int32_t(v);
  }
  // Moves past the value as OpenEXR reads it.
  void value(const std::string& name, const std::string& type, size_t end) {
    static const std::map<std::string, size_t> fixed = {
        {"box2i", 16}, {"box2f", 16}, {"chromaticities", 32}, {"compression", 1}, {"deepImageState", 1},
        {"double", 8}, {"envmap", 1}, {"float", 4}, {"int", 4}, {"keycode", 28}, {"lineOrder", 1},
        {"m33f", 36}, {"m33d", 72}, {"m44f", 64}, {"m44d", 128}, {"rational", 8}, {"tiledesc", 9},
        {"timecode", 8}, {"v2i", 8}, {"v2f", 8}, {"v2d", 16}, {"v3i", 12}, {"v3f", 12}, {"v3d", 24}};
    if (const auto it = fixed.find(type); it != fixed.end()) {
      pos_ += std::min(it->second, b_.size() - pos_);
    } else if (type == "chlist") {  // name\0 and 16 bytes per channel, an empty name last
      while (!cString("channel name").empty()) pos_ = std::min(pos_ + 16, b_.size());
    } else if (type == "preview") {  // width, height, then 4 bytes a pixel
      const uint64_t w = uint32_t(int32(name)), h = uint32_t(int32(name));
      if (w * h > (end - std::min(pos_, end)) / 4) fail(name, "declares a preview larger than the attribute");
      pos_ += size_t(4 * w * h);
    } else if (type == "stringvector") {  // int32 length and the characters, per string
      while (pos_ < end) {
        const int32_t n = int32(name);
        if (n < 0 || uint64_t(n) > end - std::min(pos_, end)) fail(name, "holds a string longer than the attribute");
        pos_ += size_t(n);
      }
    } else if (type == "idmanifest") {
      fail(name, "is of type idmanifest, which kasha does not read");
    } else {  // string, floatvector, unknown types: read at the size declared
      pos_ = end;
    }
  }

  const std::string& b_;
  const std::string& path_;
  size_t pos_ = 0;
};

// OpenEXR allocates tables by the header's data window while it opens a file, before the pixels
// are checked against the memory limit; its own sanity check bounds that: no side beyond this.
constexpr int kMaxExrSide = 65536;

}  // namespace

ExrInput::ExrInput(const std::string& path, const std::string& what)
    : bytes_(readInputFile(path, what, kMaxImageFileBytes)) {
  static const bool bounded = [] {
    Imf::Header::setMaxImageSize(kMaxExrSide, kMaxExrSide);
    Imf::Header::setMaxTileSize(kMaxExrSide, kMaxExrSide);
    return true;
  }();
  (void)bounded;
  AttributeWalk(bytes_, path).run();
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
