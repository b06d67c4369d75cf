// Writes sky.exr, the 128 × 64 equirectangular sky of fluorescent_matpreview.xml (Mitsuba's
// envmap layout: row 0 is the zenith, u = φ/2π): a blue-to-white gradient above the horizon, a
// grey-brown ground below it and a warm sun 35° above the horizon at φ = 250°, 5° across.
// Build and run from this folder:
//   g++ -std=c++20 make_sky.cpp -o /tmp/make_sky $(pkg-config --cflags --libs OpenEXR) && /tmp/make_sky
#include <ImfRgbaFile.h>

#include <cmath>
#include <vector>

int main() {
  const int w = 128, h = 64;
  const double pi = 3.14159265358979323846;
  const double sunTheta = (90.0 - 35.0) * pi / 180.0, sunPhi = 250.0 * pi / 180.0, sunRadius = 2.5 * pi / 180.0;
  std::vector<Imf::Rgba> px;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double theta = pi * (y + 0.5) / h, phi = 2.0 * pi * (x + 0.5) / w;
      // Angle to the sun from the dot product of the two directions.
      const double c = std::sin(theta) * std::sin(sunTheta) * std::cos(phi - sunPhi) + std::cos(theta) * std::cos(sunTheta);
      double r, g, b;
      if (theta < pi / 2) {
        const double t = theta / (pi / 2);  // 0 at the zenith, 1 at the horizon
        r = 0.25 + 0.55 * t, g = 0.45 + 0.45 * t, b = 0.9 + 0.1 * t;
      } else {
        r = 0.25, g = 0.22, b = 0.18;
      }
      if (std::acos(std::fmin(1.0, c)) < sunRadius) r = 400.0, g = 330.0, b = 250.0;
      px.emplace_back(float(r), float(g), float(b), 1.0f);
    }
  Imf::RgbaOutputFile out("sky.exr", w, h, Imf::WRITE_RGBA);
  out.setFrameBuffer(px.data(), 1, size_t(w));
  out.writePixels(h);
}
