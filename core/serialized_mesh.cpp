#include "core/serialized_mesh.h"

#include <zlib.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>
#include <vector>

#include "core/error.h"
#include "core/memory_budget.h"

namespace kasha {
namespace {

constexpr uint16_t kMagic = 0x041C;
constexpr uint32_t kHasNormals = 0x0001, kHasTexcoords = 0x0002, kHasColors = 0x0008, kDoublePrecision = 0x2000;
// DEFLATE's largest expansion: a 258-byte match in about 2 bits, i.e. at most 1032 output bytes a
// compressed byte (zlib's technical details, "Maximum compression factor").
constexpr uint64_t kMaxInflateRatio = 1032;
// A version 4 mesh name longer than this is not a name.
constexpr size_t kMaxNameBytes = 65536;
// What kasha holds beyond the inflated data: per vertex the decoded floats (up to 8), its position
// and Embree's copy; per triangle its indices, corner normals and uvs, twice while Shape::finalize
// drops degenerate ones, face normal, area sum, Embree's copy and BVH.
constexpr uint64_t kBytesPerVertex = 56, kBytesPerTriangle = 256;

uint64_t loadU64(const unsigned char* p) {
  uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}
uint32_t loadU32(const unsigned char* p) { return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24; }
uint16_t loadU16(const unsigned char* p) { return uint16_t(p[0] | p[1] << 8); }

// One zlib stream of the file, inflated on demand into the caller's buffers.
class Inflater {
 public:
  Inflater(const unsigned char* begin, const unsigned char* end, const std::string& path, const std::string& mesh)
      : next_(begin), end_(end), path_(path), mesh_(mesh) {
    if (inflateInit(&z_) != Z_OK) throw InputError(path_, mesh_, "zlib cannot start inflating");
  }
  ~Inflater() { inflateEnd(&z_); }
  Inflater(const Inflater&) = delete;
  Inflater& operator=(const Inflater&) = delete;

  // Up to n bytes into out; fewer only where the stream ends. Corrupt data is an InputError.
  size_t read(void* out, size_t n) {
    unsigned char* dst = static_cast<unsigned char*>(out);
    size_t got = 0;
    while (got < n && !ended_) {
      if (z_.avail_in == 0) {  // feed the compressed bytes in pieces zlib's 32-bit counts hold
        const size_t chunk = std::min<size_t>(size_t(end_ - next_), size_t(1) << 30);
        z_.next_in = const_cast<unsigned char*>(next_);
        z_.avail_in = uInt(chunk);
        next_ += chunk;
      }
      const size_t want = std::min<size_t>(n - got, size_t(1) << 30);
      z_.next_out = dst + got;
      z_.avail_out = uInt(want);
      const int status = inflate(&z_, Z_NO_FLUSH);
      got += want - z_.avail_out;
      if (status == Z_STREAM_END) {
        ended_ = true;
      } else if (status == Z_BUF_ERROR && z_.avail_in == 0 && next_ == end_) {
        throw InputError(path_, mesh_, "the compressed data is truncated");
      } else if (status != Z_OK && status != Z_BUF_ERROR) {
        throw InputError(path_, mesh_, std::string("the compressed data is corrupt (zlib: ") +
                                           (z_.msg ? z_.msg : "error " + std::to_string(status)) + ")");
      }
    }
    return got;
  }
  // Exactly n bytes, or InputError naming `field`.
  void readExactly(void* out, size_t n, const std::string& field) {
    if (read(out, n) != n) throw InputError(path_, mesh_ + ": " + field, "the mesh's data ends before it");
  }

 private:
  z_stream z_{};
  const unsigned char* next_;
  const unsigned char* end_;
  bool ended_ = false;
  const std::string& path_;
  std::string mesh_;
};

// The file offset of mesh `index`'s header, from the dictionary at the end of the file.
uint64_t meshOffset(const std::string& bytes, const std::string& path, uint16_t version, uint64_t index) {
  if (index == 0) return 0;
  const auto* b = reinterpret_cast<const unsigned char*>(bytes.data());
  const uint64_t size = bytes.size();
  if (size < 8) throw InputError(path, "dictionary", "missing: the file ends after its header");
  const uint64_t entry = version == 3 ? 4 : 8;
  const uint64_t count = loadU32(b + size - 4);
  if (saturatingMul(count, entry) > size - 8)
    throw InputError(path, "dictionary", "declares " + std::to_string(count) + " meshes, more than the file's " +
                                             std::to_string(size) + " bytes can index");
  if (index >= count)
    throw InputError(path, "shape_index", std::to_string(index) + " is out of range: the file holds " +
                                              std::to_string(count) + " meshes (0 to " + std::to_string(count - 1) + ")");
  const uint64_t dictionary = size - 4 - count * entry;
  const unsigned char* at = b + dictionary + index * entry;
  const uint64_t offset = entry == 4 ? loadU32(at) : loadU64(at);
  if (offset > dictionary || dictionary - offset < 4)
    throw InputError(path, "dictionary", "mesh " + std::to_string(index) + " starts at byte " + std::to_string(offset) +
                                             ", beyond the meshes (" + std::to_string(dictionary) + " bytes)");
  if (loadU16(b + offset) != kMagic || loadU16(b + offset + 2) != version)
    throw InputError(path, "mesh " + std::to_string(index), "no header (0x041C, version " + std::to_string(version) +
                                                                ") at byte " + std::to_string(offset));
  return offset;
}

// Reads n numbers of `bytesEach` (4: float, 8: double) from p as floats; a non-finite one is an
// InputError naming what they are.
void readFloats(const unsigned char* p, size_t n, size_t bytesEach, float* out, const std::string& path,
                const std::string& mesh, const char* what, size_t perVertex) {
  for (size_t i = 0; i < n; ++i, p += bytesEach) {
    double v;
    if (bytesEach == 8) {
      const uint64_t bits = loadU64(p);
      std::memcpy(&v, &bits, 8);
    } else {
      const uint32_t bits = loadU32(p);
      float f;
      std::memcpy(&f, &bits, 4);
      v = f;
    }
    out[i] = float(v);
    if (!std::isfinite(out[i]))
      throw InputError(path, mesh + ": vertex " + std::to_string(i / perVertex),
                       std::string(what) + " is not finite as a 32-bit float");
  }
}

}  // namespace

void readSerializedMesh(const std::string& bytes, const std::string& path, uint64_t shapeIndex, uint64_t memoryLimit,
                        Shape& s) {
  const auto* b = reinterpret_cast<const unsigned char*>(bytes.data());
  if (bytes.size() < 4 || loadU16(b) != kMagic)
    throw InputError(path, "header", "not a Mitsuba serialized mesh (it does not start with 0x041C)");
  const uint16_t version = loadU16(b + 2);
  if (version == 5) throw InputError(path, "header", "version 5 (Mitsuba 3's packed records) is not supported; versions 3 and 4 are");
  if (version != 3 && version != 4)
    throw InputError(path, "header", "unknown version " + std::to_string(version) + " (3 and 4 are read)");
  const uint64_t offset = meshOffset(bytes, path, version, shapeIndex);
  const std::string mesh = "mesh " + std::to_string(shapeIndex);
  const unsigned char* compressed = b + offset + 4;
  const uint64_t compressedBytes = bytes.size() - offset - 4;
  Inflater in(compressed, b + bytes.size(), path, mesh);

  unsigned char head[4];
  in.readExactly(head, 4, "flags");
  const uint32_t flags = loadU32(head);
  if (version == 4) {  // the name, up to its NUL
    char c = 1;
    size_t length = 0;
    while (c != 0) {
      in.readExactly(&c, 1, "name");
      if (++length > kMaxNameBytes)
        throw InputError(path, mesh + ": name", "longer than " + std::to_string(kMaxNameBytes) + " bytes");
    }
  }
  unsigned char counts[16];
  in.readExactly(counts, 16, "counts");
  const uint64_t vertices = loadU64(counts), triangles = loadU64(counts + 8);
  if (vertices == 0 || triangles == 0) throw InputError(path, mesh, "holds no triangles");
  if (vertices > uint64_t(UINT32_MAX))
    throw InputError(path, mesh + ": vertex count", std::to_string(vertices) + " is more than 32-bit indices reach");
  if (triangles > uint64_t(UINT32_MAX) / 3)
    throw InputError(path, mesh + ": face count", std::to_string(triangles) + " is more than 2^32 vertex indices");

  const size_t scalarBytes = (flags & kDoublePrecision) ? 8 : 4;
  const bool hasNormals = flags & kHasNormals, hasUvs = flags & kHasTexcoords;
  const uint64_t perVertex = 3 + (hasNormals ? 3 : 0) + (hasUvs ? 2 : 0) + ((flags & kHasColors) ? 3 : 0);
  // At most 13·8 bytes a vertex and 12 a triangle with counts below 2^32: no overflow.
  const uint64_t vertexBytes = vertices * perVertex * scalarBytes, indexBytes = triangles * 12;
  const uint64_t dataBytes = vertexBytes + indexBytes;
  if (dataBytes > saturatingMul(compressedBytes, kMaxInflateRatio))
    throw InputError(path, mesh + ": counts",
                     std::to_string(vertices) + " vertices and " + std::to_string(triangles) + " triangles need " +
                         formatBytes(dataBytes) + ", more than the " + formatBytes(compressedBytes) +
                         " of compressed data can hold");
  requireMemory(dataBytes + vertices * kBytesPerVertex + triangles * kBytesPerTriangle,
                "'" + path + "' " + mesh + " (" + std::to_string(vertices) + " vertices, " + std::to_string(triangles) +
                    " triangles)",
                memoryLimit);

  std::vector<unsigned char> data(dataBytes);
  in.readExactly(data.data(), data.size(), "data");
  unsigned char extra;
  if (in.read(&extra, 1) != 0)
    throw InputError(path, mesh, "the compressed data holds more than its counts declare");

  // Per vertex: positions, then the optional arrays in the order of the flags' bits.
  const unsigned char* p = data.data();
  std::vector<float> positions(3 * vertices), normals(hasNormals ? 3 * vertices : 0), uvs(hasUvs ? 2 * vertices : 0);
  readFloats(p, positions.size(), scalarBytes, positions.data(), path, mesh, "position", 3);
  p += positions.size() * scalarBytes;
  readFloats(p, normals.size(), scalarBytes, normals.data(), path, mesh, "normal", 3);
  p += normals.size() * scalarBytes;
  readFloats(p, uvs.size(), scalarBytes, uvs.data(), path, mesh, "texture coordinate", 2);
  p = data.data() + vertexBytes;  // vertex colours skipped

  const uint32_t base = uint32_t(s.positions.size());
  if (uint64_t(base) + vertices > uint64_t(UINT32_MAX)) throw InputError(path, mesh, "more than 2^32 vertices in one shape");
  for (uint64_t v = 0; v < vertices; ++v) s.positions.emplace_back(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
  for (uint64_t t = 0; t < triangles; ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t index = loadU32(p + 12 * t + 4 * size_t(k));
      if (index >= vertices)
        throw InputError(path, mesh + ": face " + std::to_string(t),
                         "vertex index " + std::to_string(index) + " is not below the vertex count " + std::to_string(vertices));
      s.indices.push_back(base + index);
      if (hasNormals) s.cornerNormals.emplace_back(normals[3 * index], normals[3 * index + 1], normals[3 * index + 2]);
      if (hasUvs) s.cornerUvs.emplace_back(uvs[2 * index], 1.0f - uvs[2 * index + 1]);
    }
}

}  // namespace kasha
