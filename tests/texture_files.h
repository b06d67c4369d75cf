#pragma once
// Tests of textures: a fixture that writes PNG, OpenEXR and text files into its own directory,
// and a small deterministic render of a scene file.
#include <gtest/gtest.h>

#include <ImfRgbaFile.h>
#include <png.h>

#include <fstream>
#include <string>
#include <vector>

#include "core/film.h"
#include "integrators/integrator_factory.h"
#include "integrators/render_loop.h"
#include "scene/scene_loader.h"
#include "tests/temp_dir.h"

namespace kasha::test {

class TextureFiles : public TempDirTest {
 protected:
  explicit TextureFiles(const std::string& name = "texture") : TempDirTest(name) {}

  // RGBA bytes, row 0 at the top.
  std::string writePng(const std::string& name, int w, int h, const std::vector<unsigned char>& rgba) {
    png_image img{};
    img.version = PNG_IMAGE_VERSION;
    img.width = png_uint_32(w);
    img.height = png_uint_32(h);
    img.format = PNG_FORMAT_RGBA;
    const std::string path = dir + "/" + name;
    EXPECT_TRUE(png_image_write_to_file(&img, path.c_str(), 0, rgba.data(), 0, nullptr)) << img.message;
    return path;
  }
  // One grey value per pixel (R = G = B, A = 1), row 0 at the top.
  std::string writeExr(const std::string& name, int w, int h, const std::vector<float>& grey) {
    std::vector<Vec3> rgb;
    for (const float g : grey) rgb.emplace_back(g);
    return writeRgbExr(name, w, h, rgb);
  }
  // One colour per pixel (A = 1), row 0 at the top; values are stored as half floats.
  std::string writeRgbExr(const std::string& name, int w, int h, const std::vector<Vec3>& rgb) {
    std::vector<Imf::Rgba> px;
    for (const Vec3& c : rgb) px.emplace_back(c.x, c.y, c.z, 1.0f);
    const std::string path = dir + "/" + name;
    Imf::RgbaOutputFile out(path.c_str(), w, h, Imf::WRITE_RGBA);
    out.setFrameBuffer(px.data(), 1, size_t(w));
    out.writePixels(h);
    return path;
  }
  std::string writeText(const std::string& name, const std::string& text) {
    std::ofstream(dir + "/" + name) << text;
    return dir + "/" + name;
  }
};

// XYZ of every pixel of `path` rendered by `integratorName` (4 spp, seed 5).
inline std::vector<Vec3> renderFilm(const std::string& path, const std::string& integratorName) {
  const auto scene = loadScene(path);
  const std::unique_ptr<Integrator> integrator = makeIntegrator(integratorName, *scene, scene->render);
  Film film(scene->camera.width(), scene->camera.height());
  RenderOptions opt;
  opt.spp = 4;
  opt.seed = 5;
  render(*scene, *integrator, film, opt);
  std::vector<Vec3> px;
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) px.push_back(film.xyz(x, y));
  return px;
}

}  // namespace kasha::test
