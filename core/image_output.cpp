#include "core/image_output.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <png.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "core/color.h"
#include "core/spectral_exr.h"

namespace kasha {
namespace {

std::string tempName(const std::string& path) { return path + ".tmp"; }

void commit(const std::string& tmp, const std::string& path) {
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw std::runtime_error("cannot rename '" + tmp + "' to '" + path + "': " + ec.message());
}

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
  const std::string tmp = tempName(path);
  try {
    Imf::OutputFile file(tmp.c_str(), header);
    file.setFrameBuffer(fb);
    file.writePixels(h);
  } catch (const std::exception& e) {
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot write '" + path + "': " + e.what());
  }
  commit(tmp, path);
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
  const std::string tmp = tempName(path);
  FILE* fp = std::fopen(tmp.c_str(), "wb");
  if (!fp) throw std::runtime_error("cannot write '" + path + "'");
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(fp);
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot write PNG '" + path + "'");
  }
  png_init_io(png, fp);
  png_set_IHDR(png, info, w, h, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  png_write_info(png, info);
  for (int y = 0; y < h; ++y) png_write_row(png, pixels.data() + size_t(y) * w * 3);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  if (std::fclose(fp) != 0) throw std::runtime_error("cannot write '" + path + "'");
  commit(tmp, path);
}

void writeTextFile(const std::string& path, const std::string& text) {
  const std::string tmp = tempName(path);
  {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw std::runtime_error("cannot write '" + path + "'");
    out << text;
    if (!out) throw std::runtime_error("cannot write '" + path + "'");
  }
  commit(tmp, path);
}

}  // namespace kasha
