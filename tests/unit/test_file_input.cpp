// Reading the files a user names (issue 15): one rule for every reader (core/input_file.h), the
// header of an image checked against the memory limit before decoding (core/image_input.h),
// duplicate JSON keys (core/json_parse.h), reference chains that loop or run deep, and the
// messages that name what the user wrote. Each case: the InputError's text.
#include <gtest/gtest.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfRgbaFile.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/image_input.h"
#include "core/input_file.h"
#include "core/json_parse.h"
#include "core/spectrum_csv.h"
#include "core/texture.h"
#include "scene/scene_loader.h"
#include "tests/expect_contains.h"
#include "tests/support.h"

namespace kasha {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

json baseScene() { return json::parse(test::kMinimalScene); }

// The message of the InputError that `f` throws ("no error" if none; a non-InputError fails).
template <class F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw a non-InputError: " << e.what();
  }
  return "no error";
}

class FileInput : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir = (fs::path(::testing::TempDir()) / ("kasha_file_input." + std::to_string(getpid())) / info->name()).string();
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(fs::path(dir).parent_path());
  }
  std::string write(const std::string& name, const std::string& bytes) const {
    const std::string p = dir + "/" + name;
    std::ofstream(p, std::ios::binary) << bytes;
    return p;
  }
  std::string sceneError(const json& scene) const {
    return errorOf([&] { loadSceneFromString(scene.dump(), dir + "/scene.json"); });
  }
  std::string dir;
};

TEST_F(FileInput, OnlyRegularFilesAreOpenedAndAFifoNeverBlocks) {
  const std::string fifo = dir + "/fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // Nobody writes to the FIFO: a plain open() would wait forever.
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(errorOf([&] { InputFile f(fifo, "scene file", 1000); }),
            fifo + ": cannot open scene file (a FIFO, not a regular file)");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
  EXPECT_EQ(errorOf([&] { readInputFile("/dev/zero", "scene file", 1000); }),
            "/dev/zero: cannot open scene file (a character device, not a regular file)");
  EXPECT_EQ(errorOf([&] { readInputFile(dir, "material file", 1000); }),
            dir + ": cannot open material file (a directory, not a regular file)");
  EXPECT_EQ(errorOf([&] { readInputFile(dir + "/none", "texture", 1000); }),
            dir + "/none: cannot open texture (No such file or directory)");
  // Every reader goes through it: a FIFO as a material file, a texture, a measured matrix.
  json s = baseScene();
  s["materials"]["white"] = {{"type", "file"}, {"file", "fifo"}};
  EXPECT_EQ(sceneError(s), dir + "/scene.json: /materials/white/file: " + fifo +
                               ": cannot open material file (a FIFO, not a regular file)");
  // A texture: refused at once by name, never opened for reading.
  fs::rename(fifo, dir + "/fifo.png");
  const auto texture = [](const std::string& path) {
    TextureLoader(kDefaultMemoryLimit).load(path, TextureChannel::Mean, TextureWrap::Repeat, TextureFilter::Bilinear);
  };
  const auto textureStart = std::chrono::steady_clock::now();
  EXPECT_EQ(errorOf([&] { texture(dir + "/fifo.png"); }), dir + "/fifo.png: cannot open texture (a FIFO, not a regular file)");
  EXPECT_LT(std::chrono::steady_clock::now() - textureStart, std::chrono::seconds(5));
  EXPECT_CONTAINS(errorOf([&] { texture(dir + "/none.png"); }), "No such file");
  fs::rename(dir + "/fifo.png", dir + "/fifo.exr");
  EXPECT_EQ(errorOf([&] { texture(dir + "/fifo.exr"); }), dir + "/fifo.exr: cannot open texture (a FIFO, not a regular file)");
  EXPECT_EQ(errorOf([&] { readExrXyz(dir + "/fifo.exr"); }),
            dir + "/fifo.exr: cannot open image file (a FIFO, not a regular file)");
}

TEST_F(FileInput, SizeCapAndTruncation) {
  const std::string p = write("ten.txt", "0123456789");
  EXPECT_EQ(errorOf([&] { readInputFile(p, "scene file", 9); }),
            p + ": scene file is 10 bytes, more than the 9 bytes allowed");
  EXPECT_EQ(readInputFile(p, "scene file", 10), "0123456789");
  InputFile f(p, "checkpoint file", 10);
  char buf[8];
  f.read(buf, 8);
  EXPECT_FALSE(f.atEnd());
  EXPECT_EQ(errorOf([&] { f.read(buf, 8); }), p + ": checkpoint file is truncated");
  // A scene bigger than the cap is refused before it is read (a sparse file: no disk used).
  const std::string big = write("big.json", "{}");
  fs::resize_file(big, kMaxJsonFileBytes + 1);
  EXPECT_EQ(errorOf([&] { loadScene(big); }), big + ": scene file is 64.0 MiB, more than the 64.0 MiB allowed");
}

TEST_F(FileInput, InputsAreRememberedForTheOutputChecks) {
  const std::string p = write("read.csv", "wavelength,v\n400,1\n700,1\n");
  const std::string link = dir + "/link.csv";
  fs::create_symlink(p, link);
  readSpectralCsv(link);
  EXPECT_TRUE(wasReadAsInput(p));  // the same file under another name
  EXPECT_FALSE(wasReadAsInput(dir + "/other.csv"));
}

TEST_F(FileInput, DuplicateJsonKeysAreRefused) {
  EXPECT_EQ(errorOf([] { parseJsonStrict(R"({"a": 1, "b": {"c": [1, {"d": 2, "d": 3}]}})", "s.json"); }),
            "s.json: /b/c/1/d: duplicate key 'd' (a key may appear once in an object)");
  EXPECT_EQ(errorOf([] { parseJsonStrict(R"({"camera": {}, "camera": {}})", "s.json"); }),
            "s.json: /camera: duplicate key 'camera' (a key may appear once in an object)");
  // The same key in different objects is fine.
  EXPECT_EQ(parseJsonStrict(R"({"a": {"x": 1}, "b": {"x": 2}, "c": [{"x": 3}, {"x": 4}]})", "s.json")["c"][1]["x"], 4);
  std::string text = baseScene().dump();
  const std::string white = R"("white":{"reflectance":0.5,"type":"lambertian"})";
  ASSERT_NE(text.find(white), std::string::npos) << text;
  text.replace(text.find(white), white.size(), white + "," + white);
  EXPECT_EQ(errorOf([&] { loadSceneFromString(text, "s.json"); }),
            "s.json: /materials/white: duplicate key 'white' (a key may appear once in an object)");
}

TEST_F(FileInput, MaterialFilesThatNameEachOtherAreACycleNotACrash) {
  write("self.json", R"({"type": "file", "file": "self.json"})");
  write("a.json", R"({"type": "file", "file": "b.json"})");
  write("b.json", R"({"type": "file", "file": "a.json"})");
  json s = baseScene();
  s["materials"]["white"] = {{"type", "file"}, {"file", "self.json"}};
  EXPECT_CONTAINS(sceneError(s), "material files name each other in a cycle: " + dir + "/self.json -> " + dir + "/self.json");
  s["materials"]["white"] = {{"type", "file"}, {"file", "a.json"}};
  EXPECT_CONTAINS(sceneError(s), "cycle: " + dir + "/a.json -> " + dir + "/b.json -> " + dir + "/a.json");
  // A chain without a cycle, deeper than the limit.
  for (int i = 0; i < 20; ++i)
    write("m" + std::to_string(i) + ".json", json{{"type", "file"}, {"file", "m" + std::to_string(i + 1) + ".json"}}.dump());
  write("m20.json", R"({"type": "lambertian", "reflectance": 0.5})");
  s["materials"]["white"] = {{"type", "file"}, {"file", "m0.json"}};
  EXPECT_CONTAINS(sceneError(s), "material files name each other more than 16 deep");
  s["materials"]["white"] = {{"type", "file"}, {"file", "m10.json"}};  // 10 files deep: fine
  EXPECT_EQ(sceneError(s), "no error");
}

TEST_F(FileInput, LongChainsOfNamedSpectraAreRefusedNotACrash) {
  json s = baseScene();
  // 20 000 aliases, each naming the next: the loader used to recurse until the stack overflowed.
  for (int i = 0; i < 20000; ++i) s["spectra"]["s" + std::to_string(i)] = "s" + std::to_string(i + 1);
  s["spectra"]["s20000"] = 0.5;
  const std::string msg = sceneError(s);
  EXPECT_EQ(msg.rfind(dir + "/scene.json: /spectra/", 0), 0u) << msg;
  EXPECT_CONTAINS(msg, "named spectra refer to each other more than 64 deep");
  json ok = baseScene();
  for (int i = 0; i < 30; ++i) ok["spectra"]["s" + std::to_string(i)] = "s" + std::to_string(i + 1);
  ok["spectra"]["s30"] = 0.5;
  ok["materials"]["white"]["reflectance"] = "s0";
  EXPECT_EQ(sceneError(ok), "no error");
}

TEST_F(FileInput, MessagesNameWhatTheUserWrote) {
  json s = baseScene();
  // A negative wavelength in a tabulated spectrum, or as a box's edge.
  s["materials"]["white"]["reflectance"] = {{"type", "tabulated"}, {"wavelengths", {-5, 500}}, {"values", {0.5, 0.5}}};
  EXPECT_EQ(sceneError(s), dir + "/scene.json: /materials/white/reflectance/wavelengths/0: wavelength must be positive (-5)");
  s["materials"]["white"]["reflectance"] = {{"type", "box"}, {"min", -10}, {"max", 500}, {"value", 0.5}};
  EXPECT_EQ(sceneError(s), dir + "/scene.json: /materials/white/reflectance/min: wavelength must not be negative (-10)");
  // An extreme blackbody is the temperature's fault, not the scale's.
  s = baseScene();
  s["shapes"][0]["emission"]["radiance"] = {{"type", "blackbody"}, {"kelvin", 1e37}};
  EXPECT_EQ(sceneError(s), dir + "/scene.json: /shapes/0/emission/radiance/kelvin: the blackbody spectrum overflows a 32-bit float");
  // A CSV with a UTF-8 byte order mark (spreadsheet export) reads like one without.
  const std::string bom = write("bom.csv", "\xEF\xBB\xBF# from a spreadsheet\nwavelength,v\n400,0.5\n700,0.5\n");
  EXPECT_EQ(readSpectralCsv(bom).lambdas.size(), 2u);
  // Bytes after a NUL inside a field are not silently dropped.
  const std::string nul = write("nul.csv", std::string("wavelength,v\n400,0.5\n700,0.5\0garbage\n", 38));
  EXPECT_EQ(errorOf([&] { readSpectralCsv(nul); }), nul + ":3: v: '0.5\\x00garbage' is not a number");
}

// A PNG of a few dozen bytes that declares 16000 × 16000 pixels.
std::string pngBomb() {
  const auto be32 = [](uint32_t v) {
    return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
  };
  const auto crc = [](const std::string& bytes) {  // PNG's CRC-32 (ISO 3309), bit by bit
    uint32_t c = 0xffffffffu;
    for (const unsigned char b : bytes) {
      c ^= b;
      for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
    }
    return c ^ 0xffffffffu;
  };
  const auto chunk = [&](const std::string& type, const std::string& data) {
    return be32(uint32_t(data.size())) + type + data + be32(crc(type + data));
  };
  const std::string ihdr = be32(16000) + be32(16000) + std::string{8, 2, 0, 0, 0};  // 8-bit RGB
  return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) + chunk("IDAT", std::string("\x78\x9c\x03\x00\x00\x00\x00\x01", 8)) +
         chunk("IEND", "");
}

TEST_F(FileInput, ImageHeadersAreCheckedAgainstTheMemoryLimitBeforeDecoding) {
  const std::string bomb = write("bomb.png", pngBomb());
  EXPECT_LT(fs::file_size(bomb), 100u);
  const auto texture = [](const std::string& path, uint64_t limit) {
    return TextureLoader(limit).load(path, TextureChannel::Mean, TextureWrap::Repeat, TextureFilter::Bilinear);
  };
  EXPECT_EQ(errorOf([&] { texture(bomb, uint64_t(512) << 20); }),
            bomb + ": decoding this texture (16000×16000 pixels) besides the scene's textures before it (0 bytes) "
                   "needs 2.86 GiB, more than the memory limit of 512 MiB (raise it with --memory-limit)");
  // The same through a scene: the scene's memory limit applies.
  json s = baseScene();
  s["materials"]["white"] = {{"type", "jung_fluorescent"}, {"absorption", 0.5}, {"emission", 1.0}, {"reflectance", 0.5},
                             {"c", 0.5}, {"Q", 0.5}, {"c_texture", "bomb.png"}};
  SceneLoadOptions small;
  small.memoryLimit = uint64_t(1) << 30;
  EXPECT_CONTAINS(errorOf([&] { loadSceneFromString(s.dump(), dir + "/scene.json", small); }),
                  "/materials/white/c_texture: " + bomb + ": decoding this texture (16000×16000 pixels)");
  // OpenEXR: the data window of the header decides.
  std::vector<Imf::Rgba> px(64 * 64, Imf::Rgba(0.5f, 0.5f, 0.5f, 1.0f));
  const std::string exr = dir + "/t.exr";
  {
    Imf::RgbaOutputFile out(exr.c_str(), 64, 64, Imf::WRITE_RGBA);
    out.setFrameBuffer(px.data(), 1, 64);
    out.writePixels(64);
  }
  EXPECT_EQ(errorOf([&] { texture(exr, 1024); }),
            exr + ": decoding this texture (64×64 pixels) besides the scene's textures before it (0 bytes) needs "
                  "48.0 KiB, more than the memory limit of 1.00 KiB (raise it with --memory-limit)");
  EXPECT_EQ(texture(exr, 48 * 1024)->width(), 64);
  // A header attribute declaring 2 GB in a 30-byte file: OpenEXR would allocate it before reading.
  const std::string attr = write("attr.exr", std::string("\x76\x2f\x31\x01\x02\0\0\0x\0string\0\xff\xff\xff\x7f", 22));
  EXPECT_EQ(errorOf([&] { texture(attr, kDefaultMemoryLimit); }),
            attr + ": cannot read OpenEXR: header attribute 'x' declares 2147483647 bytes, more than the file holds");
}

TEST_F(FileInput, RenderImagesWithNonFinitePixelsAreRefused) {
  // A 2×1 XYZ layer whose second pixel is NaN.
  const std::string exr = dir + "/nan.exr";
  std::vector<float> x = {0.1f, NAN}, y = {0.1f, 0.1f}, z = {0.1f, 0.1f};
  {
    Imf::Header h(2, 1);
    Imf::FrameBuffer fb;
    const char* names[3] = {"XYZ.X", "XYZ.Y", "XYZ.Z"};
    std::vector<float>* data[3] = {&x, &y, &z};
    for (int c = 0; c < 3; ++c) {
      h.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
      fb.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(data[c]->data()), sizeof(float), 2 * sizeof(float)));
    }
    Imf::OutputFile out(exr.c_str(), h);
    out.setFrameBuffer(fb);
    out.writePixels(1);
  }
  EXPECT_EQ(errorOf([&] { readExrXyz(exr); }), exr + ": pixel (1, 0) is not finite");
}

}  // namespace
}  // namespace kasha
