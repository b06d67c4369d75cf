#include "core/bispectral_exr.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "core/error.h"
#include "core/exr_input.h"
#include "core/exr_wavelength.h"
#include "core/image_input.h"

namespace kasha {

std::optional<BispectralChannel> parseBispectralChannel(const std::string& name) {
  // "T.<λ>" or "T.<λ_i>.<λ_o>": the decimal comma keeps '.' a separator.
  std::vector<std::string> parts;
  for (size_t begin = 0;;) {
    const size_t dot = name.find('.', begin);
    parts.push_back(name.substr(begin, dot == std::string::npos ? std::string::npos : dot - begin));
    if (dot == std::string::npos) break;
    begin = dot + 1;
  }
  if (parts[0] != "T" || parts.size() < 2 || parts.size() > 3) return std::nullopt;
  BispectralChannel c;
  const std::optional<float> li = parseExrWavelength(parts[1]);
  if (!li) return std::nullopt;
  c.lambdaIn = *li;
  if (parts.size() == 3) {
    const std::optional<float> lo = parseExrWavelength(parts[2]);
    if (!lo) return std::nullopt;
    c.lambdaOut = *lo;
  }
  return c;
}

BispectralData readBispectralExr(const std::string& path) {
  ExrInput exr(path, "bispectral image");
  try {
    Imf::InputFile& file = exr.file();
    const Imath::Box2i dw = file.header().dataWindow();
    std::vector<std::pair<std::string, BispectralChannel>> channels;
    std::set<float> in, out;
    for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
      const std::optional<BispectralChannel> c = parseBispectralChannel(it.name());
      if (!c) continue;
      channels.emplace_back(it.name(), *c);
      in.insert(c->lambdaIn);
      out.insert(c->lambdaOut.value_or(c->lambdaIn));
    }
    if (channels.empty())
      throw InputError(path, "", "no reflective channel T.<wavelength> or T.<wavelength>.<wavelength> (Fichet et "
                                 "al. 2021 bispectral layout)");
    // The first scanline of every channel; the measurement is its first pixel.
    const size_t width = size_t(exr.width());
    requireImageMemory(path, width, channels.size(), sizeof(float), kDefaultMemoryLimit);
    std::vector<float> line(channels.size() * width, 0.0f), values(channels.size());
    Imf::FrameBuffer fb;
    for (size_t k = 0; k < channels.size(); ++k) {
      char* base = reinterpret_cast<char*>(&line[k * width] - dw.min.x);
      fb.insert(channels[k].first, Imf::Slice(Imf::FLOAT, base, sizeof(float), 0));
    }
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.min.y);
    for (size_t k = 0; k < channels.size(); ++k) values[k] = line[k * width];
    BispectralData d;
    d.source = path;
    d.in.assign(in.begin(), in.end());
    d.out.assign(out.begin(), out.end());
    d.value.assign(d.in.size() * d.out.size(), 0.0f);
    const auto index = [](const std::vector<float>& g, float l) {
      return size_t(std::lower_bound(g.begin(), g.end(), l) - g.begin());
    };
    for (size_t k = 0; k < channels.size(); ++k) {
      const BispectralChannel& c = channels[k].second;
      if (!std::isfinite(values[k])) throw InputError(path, channels[k].first, "value is not finite");
      d.at(index(d.out, c.lambdaOut.value_or(c.lambdaIn)), index(d.in, c.lambdaIn)) = values[k];
    }
    return d;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path, "", std::string("cannot read OpenEXR: ") + e.what());
  }
}

void writeBispectralExr(const std::string& path, const BispectralData& d) {
  Imf::Header header(1, 1);
  std::vector<std::pair<std::string, float>> cells;
  for (size_t o = 0; o < d.out.size(); ++o)
    for (size_t i = 0; i < d.in.size(); ++i) {
      const bool diagonal = d.out[o] == d.in[i];
      cells.emplace_back(diagonal ? "T." + exrWavelengthName(d.in[i])
                                  : "T." + exrWavelengthName(d.in[i]) + "." + exrWavelengthName(d.out[o]),
                         d.at(o, i));
    }
  Imf::FrameBuffer fb;
  for (auto& [name, v] : cells) {
    header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    fb.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(&v), sizeof(float), sizeof(float)));
  }
  try {
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(fb);
    file.writePixels(1);
  } catch (const std::exception& e) {
    throw InputError(path, "", std::string("cannot write OpenEXR: ") + e.what());
  }
}

}  // namespace kasha
