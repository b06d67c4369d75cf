#include "core/bispectral_exr.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "core/error.h"
#include "core/exr_input.h"
#include "core/image_input.h"

namespace kasha {
namespace {

constexpr double kSpeedOfLight = 299792458.0;  // m/s

// Wavelength in nm of one part of a channel name, "<value><prefix><m|Hz>", the value written with
// a decimal comma and an optional exponent ("550,000000nm", "0,45um", "5,5e2nm", "600THz").
std::optional<float> toNanometres(const std::string& part) {
  static const std::map<std::string, double> kPrefix = {
      {"", 1.0},    {"Y", 1e24}, {"Z", 1e21}, {"E", 1e18},  {"P", 1e15}, {"T", 1e12}, {"G", 1e9}, {"M", 1e6},
      {"k", 1e3},   {"h", 1e2},  {"da", 1e1}, {"d", 1e-1},  {"c", 1e-2}, {"m", 1e-3}, {"u", 1e-6}, {"n", 1e-9},
      {"p", 1e-12}};
  const auto digit = [&](size_t k) { return k < part.size() && std::isdigit(static_cast<unsigned char>(part[k])); };
  size_t k = 0, digits = 0;
  for (; digit(k); ++k) ++digits;
  if (k < part.size() && part[k] == ',')
    for (++k; digit(k); ++k) ++digits;
  if (digits == 0) return std::nullopt;
  if (k < part.size() && (part[k] == 'e' || part[k] == 'E')) {
    const size_t sign = k + 1 < part.size() && (part[k + 1] == '+' || part[k + 1] == '-') ? 1 : 0;
    if (digit(k + 1 + sign)) {  // otherwise E is the exa prefix
      k += 1 + sign;
      while (digit(k)) ++k;
    }
  }
  std::string value = part.substr(0, k), unit = part.substr(k);
  std::replace(value.begin(), value.end(), ',', '.');
  const bool hertz = unit.size() >= 2 && unit.compare(unit.size() - 2, 2, "Hz") == 0;
  const bool metres = !hertz && !unit.empty() && unit.back() == 'm';
  if (!hertz && !metres) return std::nullopt;
  const auto prefix = kPrefix.find(unit.substr(0, unit.size() - (hertz ? 2 : 1)));
  if (prefix == kPrefix.end()) return std::nullopt;
  const double v = std::strtod(value.c_str(), nullptr) * prefix->second;
  const double m = metres ? v : kSpeedOfLight / v;
  if (!(m > 0.0) || !std::isfinite(m)) return std::nullopt;
  return float(m * 1e9);
}

std::string wavelengthName(float nm) {
  std::string s = std::to_string(double(nm));
  std::replace(s.begin(), s.end(), '.', ',');
  return s + "nm";
}

}  // namespace

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
  const std::optional<float> li = toNanometres(parts[1]);
  if (!li) return std::nullopt;
  c.lambdaIn = *li;
  if (parts.size() == 3) {
    const std::optional<float> lo = toNanometres(parts[2]);
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
      cells.emplace_back(diagonal ? "T." + wavelengthName(d.in[i])
                                  : "T." + wavelengthName(d.in[i]) + "." + wavelengthName(d.out[o]),
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
