#include "core/volume_grid.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/error.h"
#include "core/input_file.h"
#include "core/memory_budget.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>

namespace kasha {
namespace {

constexpr size_t kHeaderBytes = 48;

int32_t int32At(const unsigned char* p) {
  return int32_t(uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24);
}

float float32At(const unsigned char* p) {
  const uint32_t bits = uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
  float v;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

// The header `h` of a file of `fileSize` bytes, checked; returns the number of data bytes after it
// (all of the rest of the file), which fit the memory limit.
uint64_t checkedHeader(const unsigned char* h, uint64_t fileSize, const std::string& path, uint64_t memoryLimit,
                       std::array<int, 3>& resolution, int& channels, Vec3& boxMin, Vec3& boxMax) {
  const auto fail = [&](const std::string& reason) { throw InputError(path, "header", reason); };
  if (fileSize < kHeaderBytes)
    fail("the file is " + std::to_string(fileSize) + " bytes, shorter than the 48-byte header");
  if (h[0] != 'V' || h[1] != 'O' || h[2] != 'L') fail("not a Mitsuba volume grid (it does not start with 'VOL')");
  if (h[3] != 3) fail("unknown version " + std::to_string(int(h[3])) + " (3 is read)");
  const int32_t encoding = int32At(h + 4);
  if (encoding != 1) fail("encoding " + std::to_string(encoding) + " is not read (1: float32)");
  uint64_t values = 1;
  for (int a = 0; a < 3; ++a) {
    const int32_t n = int32At(h + 8 + 4 * a);
    if (n < 1) fail(std::string("cells along ") + "xyz"[a] + " must be at least 1, got " + std::to_string(n));
    resolution[size_t(a)] = n;
    values = saturatingMul(values, uint64_t(n));
  }
  channels = int32At(h + 20);
  if (channels != 1 && channels != 3 && channels != 6)
    fail("channels must be 1, 3 or 6, got " + std::to_string(channels));
  values = saturatingMul(values, uint64_t(channels));
  for (int a = 0; a < 3; ++a) {
    boxMin[a] = float32At(h + 24 + 4 * a);
    boxMax[a] = float32At(h + 36 + 4 * a);
    if (!std::isfinite(boxMin[a]) || !std::isfinite(boxMax[a]) || !(boxMax[a] - boxMin[a] > 0.0f))
      fail(std::string("the bounding box along ") + "xyz"[a] + " must be finite with max > min");
  }
  const uint64_t dataBytes = saturatingMul(values, sizeof(float));
  const std::string cells = std::to_string(resolution[0]) + "x" + std::to_string(resolution[1]) + "x" +
                            std::to_string(resolution[2]) + " cells of " + std::to_string(channels) + " channels";
  if (dataBytes != fileSize - kHeaderBytes)
    fail("declares " + cells + " (" + (dataBytes == UINT64_MAX ? std::string("more than 2^64") : std::to_string(dataBytes)) +
         " bytes), but " + std::to_string(fileSize - kHeaderBytes) + " bytes follow the header");
  requireMemory(dataBytes, path + ": the volume grid (" + cells + ")", memoryLimit);
  return dataBytes;
}

// The data as stored (little-endian float32) into numbers, in place; checks them and takes each
// channel's maximum.
void decodeValues(std::vector<float>& data, int channels, const std::string& path, std::vector<float>& maximum) {
  for (float& v : data) v = float32At(reinterpret_cast<const unsigned char*>(&v));
  maximum.assign(size_t(channels), 0.0f);
  for (size_t i = 0; i < data.size(); ++i) {
    if (!(data[i] >= 0.0f && std::isfinite(data[i])))
      throw InputError(path, "data", "value " + std::to_string(i / size_t(channels)) + " (channel " +
                                          std::to_string(i % size_t(channels)) + ") is " + std::to_string(data[i]) +
                                          ", not a finite number >= 0");
    float& m = maximum[i % size_t(channels)];
    m = std::max(m, data[i]);
  }
}

}  // namespace

VolumeGrid VolumeGrid::parse(const std::string& bytes, const std::string& path, uint64_t memoryLimit) {
  VolumeGrid g;
  const auto* h = reinterpret_cast<const unsigned char*>(bytes.data());
  const uint64_t dataBytes = checkedHeader(h, bytes.size(), path, memoryLimit, g.resolution_, g.channels_, g.boxMin_, g.boxMax_);
  g.data_.resize(size_t(dataBytes / sizeof(float)));
  std::memcpy(g.data_.data(), h + kHeaderBytes, size_t(dataBytes));
  decodeValues(g.data_, g.channels_, path, g.maximum_);
  return g;
}

VolumeGrid VolumeGrid::read(const std::string& path, uint64_t memoryLimit) {
  // No cap of its own: only the header is read before the data's size is checked against the
  // file's and the memory limit.
  InputFile file(path, "volume grid file", UINT64_MAX);
  unsigned char header[kHeaderBytes] = {};
  if (file.size() >= kHeaderBytes) file.read(header, kHeaderBytes);
  VolumeGrid g;
  const uint64_t dataBytes = checkedHeader(header, file.size(), path, memoryLimit, g.resolution_, g.channels_, g.boxMin_, g.boxMax_);
  g.data_.resize(size_t(dataBytes / sizeof(float)));
  file.read(g.data_.data(), size_t(dataBytes));
  decodeValues(g.data_, g.channels_, path, g.maximum_);
  return g;
}

std::optional<GridWrap> gridWrapNamed(const std::string& name) {
  if (name == "clamp") return GridWrap::Clamp;
  if (name == "repeat") return GridWrap::Repeat;
  if (name == "mirror") return GridWrap::Mirror;
  return std::nullopt;
}

glm::mat4 VolumeGrid::worldToUnit(const glm::mat4& toWorld, bool useGridBox) const {
  glm::mat4 boxToUnit(1.0f);  // the file's box onto [0, 1]³
  if (useGridBox) {
    const Vec3 size = boxMax_ - boxMin_;
    boxToUnit = glm::scale(glm::mat4(1.0f), 1.0f / size) * glm::translate(glm::mat4(1.0f), -boxMin_);
  }
  return boxToUnit * glm::inverse(toWorld);
}

namespace {

// Cell index i of an axis of n cells under `wrap`, Repeat or Mirror (Dr.Jit's texture wrap, on
// indices).
int wrappedIndex(int64_t i, int n, GridWrap wrap) {
  const int64_t period = wrap == GridWrap::Repeat ? n : 2 * int64_t(n);
  const int64_t m = ((i % period) + period) % period;
  return int(m < n ? m : period - 1 - m);
}

}  // namespace

float VolumeGrid::lookup(Vec3 u, int c, GridWrap wrap) const {
  // Cell centres at (i + 1/2)/n (Dr.Jit's textures, which Mitsuba 3's gridvolume uses): the
  // stencil is cells ⌊x⌋ and ⌊x⌋ + 1 with x = u·n − 1/2, weighted by x's fraction, each found by
  // `wrap`. A NaN coordinate (or, unless clamped, an infinite one) reads the first cell.
  std::array<int, 3> lo{}, hi{};
  std::array<float, 3> t{};
  for (int a = 0; a < 3; ++a) {
    const int n = resolution_[size_t(a)];
    if (wrap == GridWrap::Clamp) {
      // x clamped to the outermost centres: an edge cell's value exactly, with all the weight.
      float x = u[a] * float(n) - 0.5f;
      if (!(x > 0.0f)) x = 0.0f;
      if (x > float(n - 1)) x = float(n - 1);
      lo[size_t(a)] = std::min(int(x), n - 1);
      hi[size_t(a)] = std::min(lo[size_t(a)] + 1, n - 1);
      t[size_t(a)] = x - float(lo[size_t(a)]);
      continue;
    }
    double x = double(u[a]) * n - 0.5;
    if (!std::isfinite(x)) x = 0.0;
    x -= 2.0 * n * std::floor(x / (2.0 * n));  // the other modes repeat every n or 2n cells
    const double cellBelow = std::floor(x);
    lo[size_t(a)] = wrappedIndex(int64_t(cellBelow), n, wrap);
    hi[size_t(a)] = wrappedIndex(int64_t(cellBelow) + 1, n, wrap);
    t[size_t(a)] = float(x - cellBelow);
  }
  float sum = 0.0f;
  for (int corner = 0; corner < 8; ++corner) {
    float w = 1.0f;
    std::array<int, 3> i{};
    for (int a = 0; a < 3; ++a) {
      const bool upper = (corner >> a) & 1;
      i[size_t(a)] = upper ? hi[size_t(a)] : lo[size_t(a)];
      w *= upper ? t[size_t(a)] : 1.0f - t[size_t(a)];
    }
    sum += w * cell(i[0], i[1], i[2], c);
  }
  return sum;
}

}  // namespace kasha
