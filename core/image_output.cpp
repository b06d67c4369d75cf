#include "core/image_output.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <png.h>

#include <stdexcept>
#include <vector>

#include "core/color.h"
#include "core/output_file.h"
#include "core/spectral_exr.h"

namespace kasha {
namespace {

// OpenEXR's output stream over an OutputFile (every write checked, renamed when committed).
class ExrOutputStream : public Imf::OStream {
 public:
  explicit ExrOutputStream(OutputFile& file) : Imf::OStream(file.path().c_str()), file_(file) {}
  void write(const char c[], int n) override { file_.write(c, size_t(n)); }
  uint64_t tellp() override { return file_.tell(); }
  void seekp(uint64_t pos) override { file_.seek(pos); }

 private:
  OutputFile& file_;
};

// Where libpng's write callback sends the bytes, and why it failed.
struct PngSink {
  OutputFile& file;
  std::string error;
};

// libpng's write callback: a failed write becomes png_error (a longjmp back to writePng), made
// outside the catch block so that no exception is left behind by the jump.
void pngWrite(png_structp png, png_bytep data, size_t length) {
  PngSink& sink = *static_cast<PngSink*>(png_get_io_ptr(png));
  try {
    sink.file.write(data, length);
  } catch (const std::exception& e) {
    sink.error = e.what();
  }
  if (!sink.error.empty()) png_error(png, "write failed");
}
void pngFlush(png_structp) {}

}  // namespace

void writeExr(const Film& film, const std::string& path, const SpectralFilm* spectral) {
  const int w = film.width(), h = film.height();
  std::vector<float> ch[6];
  for (auto& c : ch) c.resize(size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const Vec3 xyz = film.xyz(x, y);
      const Vec3 rgb = xyzToLinearSrgb(xyz);
      const size_t i = size_t(y) * w + x;
      ch[0][i] = rgb.x, ch[1][i] = rgb.y, ch[2][i] = rgb.z;
      ch[3][i] = xyz.x, ch[4][i] = xyz.y, ch[5][i] = xyz.z;
    }
  const char* names[6] = {"R", "G", "B", "XYZ.X", "XYZ.Y", "XYZ.Z"};
  Imf::Header header(w, h);
  header.compression() = Imf::ZIP_COMPRESSION;
  Imf::FrameBuffer fb;
  for (int c = 0; c < 6; ++c) {
    header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
    fb.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(ch[c].data()), sizeof(float), sizeof(float) * w));
  }
  const auto bins = spectral ? spectralChannels(*spectral) : std::vector<std::pair<std::string, std::vector<float>>>{};
  if (spectral)
    for (const auto& [name, value] : spectralAttributes()) header.insert(name, Imf::StringAttribute(value));
  for (const auto& [name, values] : bins) {
    header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    fb.insert(name, Imf::Slice(Imf::FLOAT, const_cast<char*>(reinterpret_cast<const char*>(values.data())), sizeof(float),
                               sizeof(float) * w));
  }
  OutputFile out(path);
  try {
    ExrOutputStream stream(out);
    Imf::OutputFile file(stream, header);
    file.setFrameBuffer(fb);
    file.writePixels(h);
  } catch (const OutputError&) {  // names the file already
    throw;
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot write '" + path + "': " + e.what());
  }
  out.commit();
}

void writePng(const Film& film, const std::string& path, float exposureStops) {
  const int w = film.width(), h = film.height();
  const float gain = std::exp2(exposureStops);
  std::vector<unsigned char> pixels(size_t(w) * h * 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const Vec3 rgb = xyzToLinearSrgb(film.xyz(x, y)) * gain;
      for (int c = 0; c < 3; ++c)
        pixels[(size_t(y) * w + x) * 3 + c] = (unsigned char)(std::lround(255.0f * srgbEncode(rgb[c])));
    }
  OutputFile out(path);
  PngSink sink{out, ""};
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    // out removes its temporary file.
    throw std::runtime_error(sink.error.empty() ? "cannot write PNG '" + path + "'" : sink.error);
  }
  png_set_write_fn(png, &sink, pngWrite, pngFlush);
  png_set_IHDR(png, info, w, h, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  png_write_info(png, info);
  for (int y = 0; y < h; ++y) png_write_row(png, pixels.data() + size_t(y) * w * 3);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  out.commit();
}

void writeTextFile(const std::string& path, const std::string& text) { writeFileAtomically(path, text); }

}  // namespace kasha
