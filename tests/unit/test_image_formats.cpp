// Image formats read through stb_image (core/stb_image_input.h, chosen by core/texture.h): a tiny
// image of each format, written here (stb_image_write from the same Debian package, libpng for a
// 16-bit PNG), reads back with the values it was written with; sRGB-encoded codes are linearised
// when the texture says so and float images never are; a header forged to declare a huge image is
// refused with one line, from the header, before anything is decoded.
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <fstream>
#include <iterator>

#include "core/error.h"
#include "core/texture.h"
#include "tests/texture_files.h"

namespace kasha {
namespace {

class ImageFormats : public test::TextureFiles {
 protected:
  ImageFormats() : TextureFiles("image_formats") {}

  std::string path(const std::string& name) const { return dir + "/" + name; }
  std::string readBytes(const std::string& name) const {
    std::ifstream in(path(name), std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  void writeBytes(const std::string& name, const std::string& bytes) const {
    std::ofstream(path(name), std::ios::binary) << bytes;
  }
  // The RGB of texel (x, y) of a w×h image file.
  static Vec3 texelRgb(const std::string& file, int x, int y, int w, int h,
                       TextureEncoding encoding = TextureEncoding::Linear) {
    const auto t = TextureLoader(kDefaultMemoryLimit)
                       .load(file, TextureChannel::Rgb, TextureWrap::Clamp, TextureFilter::Nearest, encoding);
    EXPECT_EQ(t->width(), w);
    EXPECT_EQ(t->height(), h);
    return t->rgb(Vec2((float(x) + 0.5f) / float(w), 1.0f - (float(y) + 0.5f) / float(h)));
  }
};

// The sRGB transfer function's inverse (IEC 61966-2-1), written out here in double precision.
double srgbToLinear(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

// 2×2 RGBA codes, row 0 at the top: distinct values in every channel.
const unsigned char kCodes[16] = {255, 0, 51, 255, 0, 102, 204, 128, 17, 34, 68, 0, 1, 254, 128, 64};

TEST_F(ImageFormats, LosslessFormatsReadTheirCodesAsData) {
  ASSERT_TRUE(stbi_write_png(path("a.png").c_str(), 2, 2, 4, kCodes, 8));
  ASSERT_TRUE(stbi_write_tga(path("a.tga").c_str(), 2, 2, 4, kCodes));  // run-length encoded
  unsigned char rgb[12];
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < 3; ++c) rgb[3 * i + c] = kCodes[4 * i + c];
  ASSERT_TRUE(stbi_write_bmp(path("a.bmp").c_str(), 2, 2, 3, rgb));
  for (const char* name : {"a.png", "a.tga", "a.bmp"})
    for (int i = 0; i < 4; ++i) {
      const Vec3 v = texelRgb(path(name), i % 2, i / 2, 2, 2);
      EXPECT_FLOAT_EQ(v.x, float(kCodes[4 * i]) / 255.0f) << name << " pixel " << i;
      EXPECT_FLOAT_EQ(v.y, float(kCodes[4 * i + 1]) / 255.0f) << name << " pixel " << i;
      EXPECT_FLOAT_EQ(v.z, float(kCodes[4 * i + 2]) / 255.0f) << name << " pixel " << i;
    }
  // Alpha (TGA, PNG) is read too, and never sRGB-decoded.
  for (const char* name : {"a.png", "a.tga"})
    for (const TextureEncoding e : {TextureEncoding::Linear, TextureEncoding::Srgb}) {
      const auto alpha =
          TextureLoader(kDefaultMemoryLimit).load(path(name), TextureChannel::A, TextureWrap::Clamp, TextureFilter::Nearest, e);
      EXPECT_FLOAT_EQ(alpha->scalar(Vec2(0.75f, 0.75f)), 128.0f / 255.0f) << name;
    }
}

TEST_F(ImageFormats, SrgbEncodedCodesAreLinearised) {
  ASSERT_TRUE(stbi_write_png(path("a.png").c_str(), 2, 2, 4, kCodes, 8));
  for (int i = 0; i < 4; ++i) {
    const Vec3 v = texelRgb(path("a.png"), i % 2, i / 2, 2, 2, TextureEncoding::Srgb);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(v[c], srgbToLinear(kCodes[4 * i + c] / 255.0), 1e-6) << "pixel " << i << " channel " << c;
  }
  EXPECT_NEAR(texelRgb(path("a.png"), 0, 0, 2, 2, TextureEncoding::Srgb).z, 0.0331048, 1e-6) << "code 51";
}

// 16 bits per sample: 1/65535 steps, not 8-bit ones.
TEST_F(ImageFormats, SixteenBitPng) {
  const png_uint_16 codes[6] = {65535, 32768, 1, 0, 257, 65534};
  png_image img{};
  img.version = PNG_IMAGE_VERSION;
  img.width = 2;
  img.height = 1;
  img.format = PNG_FORMAT_LINEAR_RGB;  // 16-bit samples written as they are
  ASSERT_TRUE(png_image_write_to_file(&img, path("deep.png").c_str(), 0, codes, 0, nullptr)) << img.message;
  for (int x = 0; x < 2; ++x) {
    const Vec3 v = texelRgb(path("deep.png"), x, 0, 2, 1);
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(v[c], float(codes[3 * x + c]) / 65535.0f) << x << ", " << c;
  }
}

// JPEG through libjpeg-turbo (core/jpeg_input.h), written here by stb_image_write (another
// encoder): flat colours survive the DCT within a code or two; a grayscale file reads as R = G = B.
TEST_F(ImageFormats, JpegReadsColourAndGrayscale) {
  const unsigned char colour[3] = {40, 150, 220};
  std::vector<unsigned char> px;
  for (int i = 0; i < 16 * 16; ++i) px.insert(px.end(), colour, colour + 3);
  ASSERT_TRUE(stbi_write_jpg(path("a.jpg").c_str(), 16, 16, 3, px.data(), 100));
  const Vec3 v = texelRgb(path("a.jpg"), 5, 7, 16, 16);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(v[c] * 255.0f, float(colour[c]), 2.0f) << c;
  std::vector<unsigned char> gray(16 * 16, 90);
  ASSERT_TRUE(stbi_write_jpg(path("g.jpeg").c_str(), 16, 16, 1, gray.data(), 100));
  const Vec3 g = texelRgb(path("g.jpeg"), 3, 3, 16, 16);
  EXPECT_NEAR(g.x * 255.0f, 90.0f, 2.0f);
  EXPECT_EQ(g.x, g.y);
  EXPECT_EQ(g.y, g.z);
}

// A truncated file, one whose bytes are not JPEG, and a header declaring more pixels than the
// memory limit allows are each refused in one line naming the file, before any pixel is decoded.
TEST_F(ImageFormats, DamagedOrOversizedJpegIsRefused) {
  std::vector<unsigned char> px(64 * 64 * 3);
  for (size_t i = 0; i < px.size(); ++i) px[i] = (unsigned char)(i * 7);
  ASSERT_TRUE(stbi_write_jpg(path("a.jpg").c_str(), 64, 64, 3, px.data(), 90));
  const std::string whole = readBytes("a.jpg");
  writeBytes("cut.jpg", whole.substr(0, whole.size() / 2));
  writeBytes("png.jpg", "\x89PNG\r\n\x1a\nnot a jpeg");
  // The baseline frame header (SOF0: FF C0, length, precision, height, width) declares 60000×60000.
  std::string huge = whole;
  const size_t sof = huge.find("\xFF\xC0");
  ASSERT_NE(sof, std::string::npos);
  huge[sof + 5] = huge[sof + 7] = char(0xEA);
  huge[sof + 6] = huge[sof + 8] = char(0x60);
  writeBytes("huge.jpg", huge);
  const std::pair<const char*, const char*> cases[] = {
      {"cut.jpg", "cannot read JPEG: "}, {"png.jpg", "cannot read JPEG: not JPEG"}, {"huge.jpg", "60000×60000"}};
  for (const auto& [name, reason] : cases) {
    try {
      TextureLoader(uint64_t(64) << 20).load(path(name), TextureChannel::Mean, TextureWrap::Repeat, TextureFilter::Bilinear);
      ADD_FAILURE() << name << " accepted";
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(reason), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
}

// Radiance HDR holds linear floats (RGBE: exact for these values), sRGB encoding or not.
TEST_F(ImageFormats, RadianceHdrIsLinear) {
  const float values[6] = {1.0f, 0.5f, 0.25f, 0.125f, 0.75f, 0.0f};
  ASSERT_TRUE(stbi_write_hdr(path("a.hdr").c_str(), 2, 1, 3, values));
  for (const TextureEncoding e : {TextureEncoding::Linear, TextureEncoding::Srgb})
    for (int x = 0; x < 2; ++x) {
      const Vec3 v = texelRgb(path("a.hdr"), x, 0, 2, 1, e);
      for (int c = 0; c < 3; ++c) EXPECT_EQ(v[c], values[3 * x + c]) << x << ", " << c;
    }
}

// Each format's header forged to declare 16000×16000 pixels over a few bytes of data: refused for
// its size (one line naming the file), not for its missing data.
TEST_F(ImageFormats, ForgedHugeHeadersAreRefusedBeforeDecoding) {
  const unsigned char rgb[12] = {10, 20, 30, 40, 50, 60, 70, 80, 90, 100, 110, 120};
  const float hdr[12] = {0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f};
  ASSERT_TRUE(stbi_write_bmp(path("a.bmp").c_str(), 2, 2, 3, rgb));
  ASSERT_TRUE(stbi_write_tga(path("a.tga").c_str(), 2, 2, 3, rgb));
  ASSERT_TRUE(stbi_write_hdr(path("a.hdr").c_str(), 2, 2, 3, hdr));
  const uint32_t n = 16000;
  const auto le = [](std::string& b, size_t at, uint32_t v, int bytes) {
    for (int k = 0; k < bytes; ++k) b[at + size_t(k)] = char((v >> (8 * k)) & 0xff);
  };
  std::string bmp = readBytes("a.bmp");  // BITMAPINFOHEADER: width, height at 18, 22
  le(bmp, 18, n, 4);
  le(bmp, 22, n, 4);
  writeBytes("big.bmp", bmp);
  std::string tga = readBytes("a.tga");  // width, height at 12, 14
  le(tga, 12, n, 2);
  le(tga, 14, n, 2);
  writeBytes("big.tga", tga);
  std::string rad = readBytes("a.hdr");
  const size_t dims = rad.find("-Y 2 +X 2");
  ASSERT_NE(dims, std::string::npos);
  writeBytes("big.hdr", rad.replace(dims, 9, "-Y 16000 +X 16000"));
  for (const char* name : {"big.bmp", "big.tga", "big.hdr"}) {
    try {
      TextureLoader(uint64_t(64) << 20).load(path(name), TextureChannel::Mean, TextureWrap::Repeat, TextureFilter::Bilinear);
      ADD_FAILURE() << name << ": no error";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(path(name) + ": decoding this texture (16000×16000 pixels) besides the scene's textures", 0), 0u)
          << what;
      EXPECT_NE(what.find("more than the memory limit of 64.0 MiB"), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << "one line";
    }
  }
  // The same bytes with a true header decode.
  EXPECT_NO_THROW(texelRgb(path("a.bmp"), 0, 0, 2, 2));
}

// A file is read as the format its extension names (stb_image alone would take any it knows).
TEST_F(ImageFormats, WrongOrCorruptFilesNameTheFormat) {
  ASSERT_TRUE(stbi_write_bmp(path("bmp.png").c_str(), 1, 1, 3, kCodes));
  writeBytes("bad.tga", "\x00\x07 and then nothing of a TGA");
  const auto error = [&](const std::string& name) -> std::string {
    try {
      TextureLoader(kDefaultMemoryLimit).load(path(name), TextureChannel::Mean, TextureWrap::Repeat, TextureFilter::Bilinear);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_EQ(error("bmp.png"), path("bmp.png") + ": cannot read PNG: not PNG (its signature is missing)");
  EXPECT_EQ(error("bad.tga"),
            path("bad.tga") + ": cannot read TGA: corrupt, not TGA, or larger than stb_image decodes (2^30 bytes)");
}

TEST_F(ImageFormats, RunLengthEncodedHdrThatEndsEarlyIsRefusedBeforeStbLoopsOnIt) {
  // core/stb_guard.h: stb_image reads zeros past the end, and a dump of length 0 never ends its loop.
  std::vector<float> values(16 * 2 * 3, 0.25f);
  ASSERT_TRUE(stbi_write_hdr(path("full.hdr").c_str(), 16, 2, 3, values.data()));
  const std::string full = readBytes("full.hdr");
  const auto expectRefused = [&](const std::string& name) {
    try {
      TextureLoader(kDefaultMemoryLimit).load(path(name), TextureChannel::Mean, TextureWrap::Repeat, TextureFilter::Bilinear);
      ADD_FAILURE() << name << " accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), path(name) + ": cannot read Radiance HDR: a run-length encoded scanline (1) "
                                                    "holds a run of length 0, or the data ends early");
    }
  };
  writeBytes("short.hdr", full.substr(0, full.size() - 5));
  expectRefused("short.hdr");
  EXPECT_NO_THROW(TextureLoader(kDefaultMemoryLimit).load(path("full.hdr"), TextureChannel::Mean, TextureWrap::Repeat,
                                                          TextureFilter::Bilinear));
  // stb ends the header at a line that begins with a NUL byte as at an empty one (a fuzzer's find).
  std::string nulLine = full.substr(0, full.size() - 5);
  const size_t emptyLine = nulLine.find("\n\n");
  ASSERT_NE(emptyLine, std::string::npos);
  nulLine.replace(emptyLine, 2, std::string("\n\0\0\n", 4));
  writeBytes("nul.hdr", nulLine);
  expectRefused("nul.hdr");
}

}  // namespace
}  // namespace kasha
